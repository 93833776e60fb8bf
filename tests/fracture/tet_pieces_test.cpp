// A tet cut by cracks as convex pieces (src/fracture/tet_pieces.hpp), the first stage of the
// closed fragment meshes: pieces fill the tet exactly, each is closed and convex, a corner cut
// has the analytic volume, and each piece's key is the one the fragment labeller gives its points.
#include "tet_pieces.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <random>

namespace fissure::detail {
namespace {

Eigen::Matrix<double, 4, 3> unit_tet() {
  Eigen::Matrix<double, 4, 3> p;
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return p;
}

double tet_volume(const Eigen::Matrix<double, 4, 3>& p) {
  const Eigen::Vector3d a = (p.row(1) - p.row(0)).transpose(), b = (p.row(2) - p.row(0)).transpose(),
                        c = (p.row(3) - p.row(0)).transpose();
  return std::abs(a.dot(b.cross(c))) / 6.0;
}

// The labeller's code of point x (barycentric weights w) for each cut (fragment_labels.cpp,
// PieceLabeller::piece), written out again here as the oracle.
std::string labeller_key(std::span<const TetCutPlane> cuts, const Eigen::Vector4d& w) {
  const auto value = [&](const TetCutPlane& c) {
    return w(0) * c.node_values[0] + w(1) * c.node_values[1] + w(2) * c.node_values[2] + w(3) * c.node_values[3];
  };
  std::string key;
  for (const TetCutPlane& c : cuts) {
    char code = value(c) > 0.0 ? 1 : 2;
    if (c.clipped_by >= 0)
      for (const TetCutPlane& other : cuts)
        if (other.crack == c.clipped_by && c.clip_side * value(other) < 0.0) code = 0;
    key.push_back(code);
  }
  return key;
}

Eigen::Vector4d barycentric(const Eigen::Matrix<double, 4, 3>& p, const Eigen::Vector3d& x) {
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i) a.col(i) = (p.row(i + 1) - p.row(0)).transpose();
  const Eigen::Vector3d b = a.partialPivLu().solve(x - p.row(0).transpose());
  return {1.0 - b.sum(), b(0), b(1), b(2)};
}

Eigen::Vector3d vertex_mean(const TetPiece& piece) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (const auto& f : piece.faces)
    for (const auto& q : f.points) {
      sum += q;
      ++n;
    }
  return sum / n;
}

// Every directed edge of every face has its reverse, bit for bit, in another face of the piece:
// the piece's surface is closed and consistently wound.
::testing::AssertionResult closed(const TetPiece& piece) {
  using Key = std::array<double, 6>;
  std::map<Key, int> edges;
  for (const auto& f : piece.faces) {
    for (std::size_t i = 0; i < f.points.size(); ++i) {
      const auto& a = f.points[i];
      const auto& b = f.points[(i + 1) % f.points.size()];
      ++edges[{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}];
    }
  }
  for (const auto& [e, count] : edges) {
    const Key reverse{e[3], e[4], e[5], e[0], e[1], e[2]};
    const auto it = edges.find(reverse);
    if (count != 1 || it == edges.end() || it->second != 1)
      return ::testing::AssertionFailure() << "edge (" << e[0] << "," << e[1] << "," << e[2] << ")→(" << e[3] << ","
                                           << e[4] << "," << e[5] << ") used " << count << " times, its reverse "
                                           << (it == edges.end() ? 0 : it->second);
  }
  return ::testing::AssertionSuccess();
}

// Every vertex of the piece on the inner side of every face's plane (within round-off).
bool convex(const TetPiece& piece, double size) {
  for (const auto& f : piece.faces) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t i = 1; i + 1 < f.points.size(); ++i) n += (f.points[i] - f.points[0]).cross(f.points[i + 1] - f.points[0]);
    n.normalize();
    for (const auto& g : piece.faces)
      for (const auto& q : g.points)
        if (n.dot(q - f.points[0]) > 1e-9 * size) return false;
  }
  return true;
}

TEST(TetPieces, WithoutCutsTheTetIsOnePieceWoundOutward) {
  const auto p = unit_tet();
  const auto pieces = tet_pieces(p, {});
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].key, "");
  EXPECT_NEAR(piece_volume(pieces[0]), 1.0 / 6.0, 1e-15);
  EXPECT_TRUE(closed(pieces[0]));
  // Nodes in the other order (a negatively oriented tet): still wound outward.
  Eigen::Matrix<double, 4, 3> q = p;
  q.row(1).swap(q.row(2));
  EXPECT_NEAR(piece_volume(tet_pieces(q, {})[0]), 1.0 / 6.0, 1e-15);
}

TEST(TetPieces, ACornerCutHasTheAnalyticVolume) {
  // Node 0 alone on the positive side: the plane meets edge 0–i at t_i = a/(a + b_i), and the
  // corner piece is the tet scaled by t_i along each edge: volume V·t1·t2·t3.
  const TetCutPlane cut{7, {0.3, -0.7, -0.2, -1.1}, -1, 0};
  const auto pieces = tet_pieces(unit_tet(), std::span(&cut, 1));
  ASSERT_EQ(pieces.size(), 2u);
  const double t1 = 0.3 / 1.0, t2 = 0.3 / 0.5, t3 = 0.3 / 1.4;
  for (const auto& piece : pieces) {
    EXPECT_TRUE(closed(piece));
    ASSERT_EQ(piece.key.size(), 1u);
    const double expected = piece.key[0] == 1 ? t1 * t2 * t3 / 6.0 : (1.0 - t1 * t2 * t3) / 6.0;
    // Relative 1e-13: a few roundings of numbers of size 1.
    EXPECT_NEAR(piece_volume(piece), expected, 1e-13);
    int crack_faces = 0;
    for (const auto& f : piece.faces) crack_faces += f.kind == PieceFaceKind::Crack && f.index == 7;
    EXPECT_EQ(crack_faces, 1);
  }
}

TEST(TetPieces, AClippedCrackDividesOnlyItsArrivalSide) {
  // Crack 1 splits the tet in x; crack 4 (a T on crack 1) exists only where crack 1 is positive.
  const auto p = unit_tet();
  const std::array<TetCutPlane, 2> cuts{TetCutPlane{1, {-0.25, 0.75, -0.25, -0.25}, -1, 0},   // x − 0.25
                                        TetCutPlane{4, {-0.1, -0.1, 0.9, -0.1}, 1, 1}};      // y − 0.1
  const auto pieces = tet_pieces(p, cuts);
  ASSERT_EQ(pieces.size(), 3u);
  std::map<std::string, double> volume;
  for (const auto& piece : pieces) {
    EXPECT_TRUE(closed(piece));
    volume[piece.key] = piece_volume(piece);
  }
  // x < 0.25: crack 4 absent (code 0); x > 0.25 split at y = 0.1.
  const std::string absent{2, 0}, above{1, 1}, below{1, 2};
  ASSERT_EQ(volume.count(absent), 1u);
  ASSERT_EQ(volume.count(above), 1u);
  ASSERT_EQ(volume.count(below), 1u);
  // x > 0.25 is the corner at node 1 scaled by 0.75: 0.75³/6.
  EXPECT_NEAR(volume[above] + volume[below], std::pow(0.75, 3) / 6.0, 1e-13);
}

// Random tets, 1–4 random cuts, about a third of them clipped by an earlier one: the pieces fill
// the tet, each is closed and convex, and the labeller puts each piece's inner point in it.
TEST(TetPieces, RandomCutsFillTheTetWithClosedConvexPiecesWhoseKeysMatchTheLabeller) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Eigen::Matrix<double, 4, 3> p;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) p(i, j) = unit(rng);
    const double v = tet_volume(p);
    if (v < 1e-3) continue;  // slivers have their own test
    std::vector<TetCutPlane> cuts;
    const int count = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < count; ++k) {
      TetCutPlane c;
      c.crack = 10 * k + 3;
      for (double& x : c.node_values) x = unit(rng);
      if (k > 0 && rng() % 3 == 0) {
        c.clipped_by = cuts[rng() % cuts.size()].crack;
        c.clip_side = rng() % 2 ? 1 : -1;
      }
      cuts.push_back(c);
    }
    const auto pieces = tet_pieces(p, cuts);
    double total = 0.0;
    const double size = (p.colwise().maxCoeff() - p.colwise().minCoeff()).maxCoeff();
    for (const auto& piece : pieces) {
      ASSERT_TRUE(closed(piece)) << "trial " << trial;
      ASSERT_TRUE(convex(piece, size)) << "trial " << trial;
      const double pv = piece_volume(piece);
      ASSERT_GT(pv, 0.0) << "trial " << trial;
      total += pv;
      EXPECT_EQ(labeller_key(cuts, barycentric(p, vertex_mean(piece))), piece.key) << "trial " << trial;
    }
    // Pieces thinner than 1e-12 of the tet are dropped; the rest is round-off of sums of size v.
    EXPECT_NEAR(total, v, 1e-11 * v) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

// Two tets sharing face (A, B, C), numbered differently, cut by the same two cracks (one node
// value per global node): the points their pieces put on the shared face are the same bits.
TEST(TetPieces, TetsSharingAFacePutTheSamePointsOnIt) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    // Global nodes 0..4: A, B, C shared; D and E on either side of the face.
    std::array<Eigen::Vector3d, 5> x{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                     Eigen::Vector3d(0.2, 0.3, 1), Eigen::Vector3d(0.3, 0.2, -1)};
    for (auto& p : x) p += 0.1 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    std::array<std::array<double, 5>, 2> value{};
    for (auto& crack : value)
      for (double& v : crack) v = unit(rng);
    const std::array<std::array<int, 4>, 2> tets{{{3, 0, 1, 2}, {1, 4, 2, 0}}};  // global ids per local node
    std::array<std::set<std::array<double, 3>>, 2> on_face;
    for (int t = 0; t < 2; ++t) {
      Eigen::Matrix<double, 4, 3> nodes;
      std::vector<TetCutPlane> cuts(2);
      TetPieceOptions options;
      options.on_plane = 1e-12;  // one value for both tets
      for (int i = 0; i < 4; ++i) {
        nodes.row(i) = x[static_cast<std::size_t>(tets[t][i])].transpose();
        for (int k = 0; k < 2; ++k) cuts[k].node_values[i] = value[k][static_cast<std::size_t>(tets[t][i])];
      }
      cuts[0].crack = 0;
      cuts[1].crack = 1;
      std::iota(options.node_order.begin(), options.node_order.end(), 0);
      std::sort(options.node_order.begin(), options.node_order.end(),
                [&](int a, int b) { return tets[t][a] < tets[t][b]; });
      const int apex = t == 0 ? 0 : 1;  // the local node off the shared face
      for (const auto& piece : tet_pieces(nodes, cuts, options))
        for (const auto& f : piece.faces)
          for (std::size_t i = 0; i < f.points.size(); ++i)
            if (f.weights[i](apex) == 0.0) on_face[t].insert({f.points[i].x(), f.points[i].y(), f.points[i].z()});
    }
    ASSERT_EQ(on_face[0], on_face[1]) << "trial " << trial;
  }
}

TEST(TetPieces, SliversAndNearlyTouchingCutsStayFiniteAndFillTheTet) {
  // A tet 1e-7 thick, and a cut whose plane passes within 1e-14 of a node.
  Eigen::Matrix<double, 4, 3> p;
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, 1e-7;
  const std::array<TetCutPlane, 2> cuts{TetCutPlane{0, {1e-14, -1.0, -1.0, 0.5}, -1, 0},
                                        TetCutPlane{1, {-0.5, 0.5, -0.5, 0.5}, -1, 0}};
  const auto pieces = tet_pieces(p, cuts);
  double total = 0.0;
  for (const auto& piece : pieces) {
    for (const auto& f : piece.faces)
      for (const auto& q : f.points) ASSERT_TRUE(q.allFinite());
    EXPECT_TRUE(closed(piece));
    total += piece_volume(piece);
  }
  EXPECT_NEAR(total, tet_volume(p), 1e-9 * tet_volume(p));
}

}  // namespace
}  // namespace fissure::detail
