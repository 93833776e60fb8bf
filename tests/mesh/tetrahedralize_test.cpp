#include "fissure/base/error.hpp"
#include "fissure/base/memory.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"

#include "curved_shapes.hpp"
#include "test_shapes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

namespace fissure {
namespace {

TEST(Tile, ParsesAndRefuses) {
  const TileSpec t = parse_tile_spec("tile:1,0.5,0.05");
  EXPECT_DOUBLE_EQ(t.width, 1.0);
  EXPECT_DOUBLE_EQ(t.height, 0.5);
  EXPECT_DOUBLE_EQ(t.thickness, 0.05);
  EXPECT_TRUE(is_tile_spec("tile:1,1,1"));
  EXPECT_FALSE(is_tile_spec("tile.obj"));
  for (const char* bad : {"tile:1,1", "tile:1,1,0", "tile:1,-1,1", "tile:a,1,1", "tile:1,1,1,1", "tile:1,1,inf"}) {
    try {
      parse_tile_spec(bad);
      FAIL() << bad;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

// The tile spec is read by the one list parser (base/number_text.hpp); each refusal names the
// spec and what is wrong with it. Main's own parser said "sizes must be positive and finite" for
// both -1 and nan, without saying which size.
TEST(Tile, RefusalsSayWhatIsWrong) {
  auto refusal = [](const char* spec) {
    try {
      parse_tile_spec(spec);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal("tile:1,1"), "tile 'tile:1,1': expected 3 numbers W,H,T (metres), got 2");
  EXPECT_EQ(refusal("tile:1,x,1"), "tile 'tile:1,x,1': 'x' is not a finite number");
  EXPECT_EQ(refusal("tile:1,1,-1"), "tile 'tile:1,1,-1': thickness T -1 must be positive");
  EXPECT_EQ(refusal("tile:nan,1,1"), "tile 'tile:nan,1,1': 'nan' is not a finite number");
  EXPECT_EQ(refusal("tile:1, 2 ,3"), "accepted");
  EXPECT_EQ(make_tile_surface(parse_tile_spec("tile:1e-6,2e-6,5e-7")).source_name, "tile:1e-06,2e-06,5e-07");
}

TEST(Tile, SurfaceIsClosedOutwardAndExact) {
  const SurfaceMesh s = make_tile_surface({0.8, 0.6, 0.05});
  EXPECT_NEAR(signed_volume(s), 0.8 * 0.6 * 0.05, 1e-16);
  EXPECT_NEAR(surface_area(s), 2 * (0.8 * 0.6 + 0.8 * 0.05 + 0.6 * 0.05), 1e-15);
  // Every directed edge appears once and its reverse once: closed and consistently oriented.
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < s.face_count(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{s.faces(f, k), s.faces(f, (k + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  // The conventions of tile.hpp.
  EXPECT_DOUBLE_EQ(s.vertices.col(2).minCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(s.vertices.col(2).maxCoeff(), 0.05);
  EXPECT_DOUBLE_EQ(s.vertices.col(0).minCoeff(), -0.4);
}

// Every boundary face of the tet mesh lies on one of the box's six planes.
void expect_boundary_on_box(const TetMesh& m, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  // CGAL places surface vertices by intersecting with the input planes in double: 1e-12 of the
  // box size covers that round-off.
  const double tol = 1e-12 * (hi - lo).norm();
  for (const BoundaryFace& f : m.boundary_faces()) {
    bool on_a_plane = false;
    for (int axis = 0; axis < 3 && !on_a_plane; ++axis) {
      for (double plane : {lo[axis], hi[axis]}) {
        bool all = true;
        for (int v : f.nodes) all = all && std::abs(m.nodes()(v, axis) - plane) <= tol;
        on_a_plane = on_a_plane || all;
      }
    }
    ASSERT_TRUE(on_a_plane) << "boundary face of tet " << f.tet << " is not on the box";
  }
}

TEST(Tetrahedralize, TileIsFilledExactly) {
  TetrahedralizeOptions options;
  options.target_tets = 4000;
  TetrahedralizeReport report;
  const TetMesh m = tetrahedralize(make_tile_surface({1.0, 1.0, 0.2}), options, &report);
  // Sharp features are protected, so the box is reproduced exactly: the volume differs only by
  // the round-off of summing ~4000 tet volumes (~1e-15 relative).
  EXPECT_NEAR(m.total_volume(), 0.2, 1e-13);
  EXPECT_NEAR(m.tet_count(), 4000, 0.25 * 4000);
  EXPECT_GE(report.quality.min_dihedral_deg, 10.0) << "perturb + exude target 12 deg";
  EXPECT_EQ(m.component_count(), 1);
  expect_boundary_on_box(m, {-0.5, -0.5, 0.0}, {0.5, 0.5, 0.2});
  EXPECT_TRUE(report.warnings.empty());
}

TEST(Tetrahedralize, ThinTileKeepsItsCornersAndVolume) {
  TetrahedralizeOptions options;
  options.target_tets = 8000;
  TetrahedralizeReport report;
  const TetMesh m = tetrahedralize(make_tile_surface({0.5, 0.5, 0.05}), options, &report);
  EXPECT_NEAR(m.total_volume(), 0.5 * 0.5 * 0.05, 1e-14);
  expect_boundary_on_box(m, {-0.25, -0.25, 0.0}, {0.25, 0.25, 0.05});
  // The 8 corners are mesh nodes (features protected).
  for (int i = 0; i < 8; ++i) {
    const Eigen::RowVector3d corner((i & 1) ? 0.25 : -0.25, (i & 2) ? 0.25 : -0.25, (i & 4) ? 0.05 : 0.0);
    EXPECT_LT((m.nodes().rowwise() - corner).rowwise().norm().minCoeff(), 1e-12);
  }
}

// A user's 12-triangle box centred on the origin (0.4 × 0.4 × 0.03 m, as an OBJ exported from a
// modeller): at 3000 tets sliver removal left a cell of zero volume with its four corners on
// the top face (cocircular boundary vertices), and the mesher threw. Such a cell is dropped (the
// facets behind it cover the same part of the face), so the box is filled exactly.
TEST(Tetrahedralize, FlatCellOnAFaceIsDroppedAndTheBoxStaysFilled) {
  SurfaceMesh box;
  box.vertices.resize(8, 3);
  // Vertex i: bit 2 → +x, bit 1 → +y, bit 0 → +z; each face a fan from its first corner.
  for (int i = 0; i < 8; ++i) box.vertices.row(i) << ((i & 4) ? 0.2 : -0.2), ((i & 2) ? 0.2 : -0.2), ((i & 1) ? 0.015 : -0.015);
  box.faces.resize(12, 3);
  box.faces << 1, 5, 7, 1, 7, 3,  // top
      0, 2, 6, 0, 6, 4,           // bottom
      4, 6, 7, 4, 7, 5,           // +x
      0, 1, 3, 0, 3, 2,           // −x
      2, 3, 7, 2, 7, 6,           // +y
      0, 4, 5, 0, 5, 1;           // −y
  TetrahedralizeOptions options;
  options.target_tets = 3000;
  const TetMesh m = tetrahedralize(box, options);
  EXPECT_NEAR(m.total_volume(), 0.4 * 0.4 * 0.03, 1e-15);  // round-off of ~3000 tet volumes
  EXPECT_EQ(m.component_count(), 1);
  expect_boundary_on_box(m, {-0.2, -0.2, -0.015}, {0.2, 0.2, 0.015});
  double area = 0.0;
  for (const BoundaryFace& f : m.boundary_faces()) area += f.area;
  EXPECT_NEAR(area, 2.0 * 0.4 * 0.4 + 4.0 * 0.4 * 0.03, 1e-12);  // no face covered twice
}

TEST(Tetrahedralize, SameInputSameMesh) {
  TetrahedralizeOptions options;
  options.target_tets = 3000;
  const SurfaceMesh s = make_tile_surface({1.0, 0.5, 0.25});
  const TetMesh a = tetrahedralize(s, options);
  const TetMesh b = tetrahedralize(s, options);
  ASSERT_EQ(a.node_count(), b.node_count());
  EXPECT_TRUE(a.nodes() == b.nodes());  // bitwise
  EXPECT_TRUE(a.tets() == b.tets());
}

TEST(Tetrahedralize, NonConvexSurface) {
  const SurfaceMesh s = test::l_prism();
  ASSERT_NEAR(signed_volume(s), 1.5, 1e-15);
  TetrahedralizeOptions options;
  options.target_tets = 3000;
  const TetMesh m = tetrahedralize(s, options);
  EXPECT_NEAR(m.total_volume(), 1.5, 1e-12);
  // No tet centroid falls in the notch (x > 1 and y > 1).
  for (int t = 0; t < m.tet_count(); ++t) {
    const Eigen::Vector3d c = m.centroid(t);
    ASSERT_FALSE(c.x() > 1.0 && c.y() > 1.0) << "tet " << t << " fills the notch";
  }
}

// Boundary area of a tet mesh, m².
double boundary_area(const TetMesh& m) {
  double a = 0.0;
  for (const BoundaryFace& f : m.boundary_faces()) a += f.area;
  return a;
}

// Coarse requests used to leave a thin tile hollow: on main, tile:1,1,0.05 at 10–500 tets came
// back with 2771 tets and 0.018 of its 0.05 m³ (2000 tets: 0.0459 m³). CGAL dropped the cells
// whose circumcentres lay outside the plate because the size bound exceeded the thickness.
TEST(Tetrahedralize, CoarseThinTileKeepsItsVolume) {
  TetrahedralizeOptions options;
  // Sliver removal on a plate one or two tets thick runs for seconds (issue 9); filling does not
  // depend on it, so it is kept short here.
  options.perturb_time_limit_s = 0.5;
  options.exude_time_limit_s = 0.5;
  for (int target : {10, 100, 500, 2000}) {
    options.target_tets = target;
    TetrahedralizeReport report;
    const TetMesh m = tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options, &report);
    // Box faces are protected and reproduced exactly: only round-off of the volume sum remains.
    EXPECT_NEAR(m.total_volume(), 0.05, 1e-13) << target << " tets asked for";
    EXPECT_NEAR(boundary_area(m), 2.0 * (1.0 + 2 * 0.05), 1e-12) << target;
    expect_boundary_on_box(m, {-0.5, -0.5, 0.0}, {0.5, 0.5, 0.05});
    if (target < 2000) {
      // A plate cannot hold so few tets: it gets the coarsest mesh that fills it, and says so.
      ASSERT_EQ(report.warnings.size(), 1u) << target;
      EXPECT_NE(report.warnings[0].find(" tets instead of the " + std::to_string(target) + " asked for"),
                std::string::npos)
          << report.warnings[0];
    }
  }
}

// A 1 µm cube: volume and all six faces kept at every resolution (main lost two faces and 17 %).
TEST(Tetrahedralize, MicronCubeIsFilled) {
  TetrahedralizeOptions options;
  for (int target : {10, 300, 3000}) {
    options.target_tets = target;
    const TetMesh m = tetrahedralize(make_tile_surface({1e-6, 1e-6, 1e-6}), options);
    // Relative round-off of the volume sum, as for the metre-sized tiles (1e-13 of 1 m³).
    EXPECT_NEAR(m.total_volume() / 1e-18, 1.0, 1e-12) << target;
    EXPECT_NEAR(boundary_area(m) / 6e-12, 1.0, 1e-12) << target;
    expect_boundary_on_box(m, {-0.5e-6, -0.5e-6, 0.0}, {0.5e-6, 0.5e-6, 1e-6});
  }
}

// The same body at 1 µm, 1 m and 1 km scale gets the same mesh up to scale: Fissure meshes a
// copy scaled by a power of two, so only the rounding of the input coordinates differs.
TEST(Tetrahedralize, ScaleInvariant) {
  TetrahedralizeOptions options;
  options.target_tets = 2000;
  std::vector<int> counts;
  for (double scale : {1e-6, 1.0, 1e3}) {
    const TetMesh m = tetrahedralize(make_tile_surface({scale, 0.5 * scale, 0.25 * scale}), options);
    const double volume = 0.125 * scale * scale * scale;
    EXPECT_NEAR(m.total_volume() / volume, 1.0, 1e-12) << scale;
    counts.push_back(m.tet_count());
  }
  for (int c : counts) {
    EXPECT_NEAR(c, 2000, 0.25 * 2000);
    // Same band: the meshes differ only where input rounding tips a Delaunay decision.
    EXPECT_NEAR(c, counts[1], 0.05 * counts[1]);
  }
}

// tile:10,10,0.01 at the default 24000 tets ran 86 s (2 min here) and then failed with "tet
// 90247 has zero volume". It is now refused at once with the reason and the count it needs.
TEST(Tetrahedralize, RefusesASizeTheBodyCannotHold) {
  TetrahedralizeOptions options;
  const auto start = std::chrono::steady_clock::now();
  try {
    tetrahedralize(make_tile_surface({10.0, 10.0, 0.01}), options);
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tile:10,10,0.01: 24000 tets would be about 0.0574 m across, too coarse for a body "
                        "0.00998 m thick"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("at least about 2.3e+06 tets"), std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

// Requests beyond the memory limit are refused before any work, with the estimate.
TEST(Tetrahedralize, RefusesRequestsBeyondTheMemoryLimit) {
  TetrahedralizeOptions options;
  options.target_tets = 50'000'000;
  options.memory_limit_bytes = 16'000'000'000;
  try {
    tetrahedralize(make_tile_surface({1, 1, 1}), options);
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedralize: 5e+07 tets needs about " +
                                         format_bytes(tetrahedralize_memory_estimate(50'000'000)) +
                                         ", more than the 16 GB allowed"),
              std::string::npos)
        << e.what();
  }
  // The slope stays within the measured 630–650 bytes per tet plus its margin (peak RSS, see
  // tetrahedralize.cpp), and a small request passes a limit just above its estimate.
  const double per_tet = (tetrahedralize_memory_estimate(2'000'000) - tetrahedralize_memory_estimate(1'000'000)) / 1e6;
  EXPECT_GE(per_tet, 630.0);
  EXPECT_LE(per_tet, 1000.0);
  options.target_tets = 200;
  options.memory_limit_bytes = static_cast<std::uint64_t>(tetrahedralize_memory_estimate(200)) + 1;
  EXPECT_NO_THROW(tetrahedralize(make_tile_surface({1, 1, 1}), options));
}

class RecordingProgress final : public ProgressSink {
public:
  void report(std::string_view stage, double fraction) override {
    std::lock_guard lock(m_mutex);
    EXPECT_EQ(stage, "tetrahedralize");
    fractions.push_back(fraction);
  }
  std::vector<double> fractions;

private:
  std::mutex m_mutex;
};

// Progress comes from inside CGAL's refinement, not only between attempts (main: one report per
// attempt and one at the end), and rises monotonically to 1. The watch reports at most every
// 200 ms, so the request must refine for longer than that: 100K tets in a cube take about a
// second (30K took 0.3 s once refinement alone was timed, too close to the interval).
TEST(Tetrahedralize, ReportsProgressDuringRefinement) {
  TetrahedralizeOptions options;
  options.target_tets = 100000;
  RecordingProgress progress;
  TetrahedralizeReport report;
  tetrahedralize(make_tile_surface({1, 1, 1}), options, &report, &progress);
  ASSERT_EQ(report.attempts, 1);
  int inside = 0;
  for (double f : progress.fractions) inside += f > 0.0 && f < 0.4;  // refinement of attempt 1
  EXPECT_GE(inside, 1) << "no report during refinement";
  EXPECT_TRUE(std::is_sorted(progress.fractions.begin(), progress.fractions.end()));
  EXPECT_EQ(progress.fractions.back(), 1.0);
}

// A cancel from another thread stops CGAL's refinement itself (through Mesh_3's stop flag): a
// 2M-tet mesh (about a minute) ends within a second of the cancel. Main only looked between
// attempts, so the cancel waited for the whole refinement.
TEST(Tetrahedralize, CancelFromAnotherThreadStopsRefinement) {
  TetrahedralizeOptions options;
  options.target_tets = 2'000'000;
  CancelToken cancel;
  std::chrono::steady_clock::time_point cancelled_at;
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    cancelled_at = std::chrono::steady_clock::now();
    cancel.cancel();
  });
  EXPECT_THROW(tetrahedralize(make_tile_surface({1, 1, 1}), options, nullptr, nullptr, &cancel), Cancelled);
  const auto ended = std::chrono::steady_clock::now();
  canceller.join();
  // 2 s: a refinement step is microseconds, freeing the partial triangulation a few hundred ms
  // on a loaded machine.
  EXPECT_LT(ended - cancelled_at, std::chrono::seconds(2));
}

// Sliver removal reads the cancel token through a watch on CGAL's perturber and exuder (their
// free functions read none). Without a cancel the watched passes must give CGAL's own result:
// the same nodes and tets, bit for bit, as the free functions (which run when no token is
// given). Sliver removal must change this mesh, or the comparison would prove nothing.
TEST(Tetrahedralize, SliverRemovalWatchKeepsTheMesh) {
  TetrahedralizeOptions options;
  options.target_tets = 24000;
  // No time limits: a pass stopped by the clock (10 s, reached under AddressSanitizer on larger
  // meshes) would end at a different step in each run.
  options.perturb_time_limit_s = 0.0;
  options.exude_time_limit_s = 0.0;
  const SurfaceMesh tile = make_tile_surface({1, 1, 0.05});
  CancelToken never;
  TetrahedralizeReport plain_report, watched_report;
  const TetMesh plain = tetrahedralize(tile, options, &plain_report);
  const TetMesh watched = tetrahedralize(tile, options, &watched_report, nullptr, &never);
  ASSERT_EQ(plain.node_count(), watched.node_count());
  ASSERT_EQ(plain.tet_count(), watched.tet_count());
  EXPECT_TRUE(plain.nodes() == watched.nodes()) << "node coordinates differ";
  EXPECT_TRUE(plain.tets() == watched.tets()) << "tets differ";
  options.sliver_bound_deg = 1e-6;  // nothing is a sliver: perturbation and exudation do nothing
  options.refuse_below_dihedral_deg = 0.0;
  const TetMesh unoptimised = tetrahedralize(tile, options, nullptr, nullptr, &never);
  EXPECT_FALSE(unoptimised.node_count() == plain.node_count() && unoptimised.nodes() == plain.nodes() &&
               unoptimised.tets() == plain.tets())
      << "sliver removal changed nothing: the comparison above is vacuous";
  std::printf("min dihedral %.2f deg with sliver removal, %.2f deg without\n", plain_report.quality.min_dihedral_deg,
              unoptimised.quality().min_dihedral_deg);
}

// Times the two sliver removal passes of the first attempt from its progress reports (its
// refinement reports below 0.4 · 0.95; perturbation runs in [0.4, 0.45), exudation in
// [0.45, 0.5), a second attempt from 0.5 on), and raises `cancel` `delay` after the start of
// pass `cancel_in` (0 perturbation, 1 exudation), from another thread (at once when 0).
class SliverPassProgress final : public ProgressSink {
public:
  SliverPassProgress(CancelToken* cancel, int cancel_in, std::chrono::milliseconds delay)
      : m_cancel(cancel), m_cancel_in(cancel_in), m_delay(delay) {}
  ~SliverPassProgress() override { join(); }
  void report(std::string_view, double fraction) override {
    const auto now = std::chrono::steady_clock::now();
    const double starts[] = {0.4, 0.45, 0.5};
    for (int k = 0; k < 3; ++k) {
      if (fraction < starts[k] || m_seen[k]) continue;
      m_seen[k] = true;
      pass_start[k] = now;
      if (m_cancel && k == m_cancel_in && m_delay.count() == 0) {
        cancelled_at = now;
        m_cancel->cancel();
      } else if (m_cancel && k == m_cancel_in) {
        m_canceller = std::thread([this] {
          std::this_thread::sleep_for(m_delay);
          cancelled_at = std::chrono::steady_clock::now();
          m_cancel->cancel();
        });
      }
    }
  }
  void join() {
    if (m_canceller.joinable()) m_canceller.join();
  }
  std::chrono::milliseconds pass_time(int k) const {
    return std::chrono::duration_cast<std::chrono::milliseconds>(pass_start[k + 1] - pass_start[k]);
  }
  std::chrono::steady_clock::time_point pass_start[3], cancelled_at;

private:
  CancelToken* m_cancel;
  int m_cancel_in;
  std::chrono::milliseconds m_delay;
  bool m_seen[3] = {false, false, false};
  std::thread m_canceller;
};

// A cancel raised during sliver removal ends the call within 0.5 s. Main read the token only
// after both passes, so the cancel waited for the rest of them (up to their 10 s time limits).
// On the 1 × 1 × 0.05 m tile at 150K tets perturbation takes about a second: the cancel comes
// a third into it, so main would have taken over 0.5 s more. Exudation takes 16 ms after it
// (150 ms with perturbation cut to 1 ms), too short to time a cancel inside it: a cancel
// raised as it starts must stop it, on a 50K mesh.
TEST(Tetrahedralize, CancelDuringSliverRemovalIsPrompt) {
#if defined(__SANITIZE_ADDRESS__)
  // A timing test: under AddressSanitizer perturbation runs into its 10 s limit and the test
  // takes 70 s; the watched passes themselves run there in SliverRemovalWatchKeepsTheMesh.
  GTEST_SKIP() << "timing test, skipped under AddressSanitizer";
#endif
  const SurfaceMesh tile = make_tile_surface({1, 1, 0.05});
  {
    TetrahedralizeOptions options;
    options.target_tets = 100000;
    options.sliver_bound_deg = 15.0;
    SliverPassProgress timing(nullptr, -1, {});
    TetrahedralizeReport report;
    tetrahedralize(tile, options, &report, &timing);
    ASSERT_EQ(report.attempts, 1);
    std::printf("uncancelled: perturbation %lld ms, exudation %lld ms\n", static_cast<long long>(timing.pass_time(0).count()),
                static_cast<long long>(timing.pass_time(1).count()));
    ASSERT_GT(timing.pass_time(0), std::chrono::milliseconds(800)) << "perturbation too short to test";
    CancelToken cancel;
    SliverPassProgress progress(&cancel, 0, timing.pass_time(0) / 3);
    EXPECT_THROW(tetrahedralize(tile, options, nullptr, &progress, &cancel), Cancelled);
    const auto ended = std::chrono::steady_clock::now();
    progress.join();
    const double latency = std::chrono::duration<double>(ended - progress.cancelled_at).count();
    std::printf("cancel a third into perturbation: Cancelled %.1f ms later\n", 1e3 * latency);
    EXPECT_LT(latency, 0.5);
  }
  {
    TetrahedralizeOptions options;
    options.target_tets = 50000;
    options.perturb_time_limit_s = 1e-3;
    CancelToken cancel;
    SliverPassProgress progress(&cancel, 1, std::chrono::milliseconds(0));
    EXPECT_THROW(tetrahedralize(tile, options, nullptr, &progress, &cancel), Cancelled);
    const double latency = std::chrono::duration<double>(std::chrono::steady_clock::now() - progress.cancelled_at).count();
    std::printf("cancel as exudation starts: Cancelled %.1f ms later\n", 1e3 * latency);
    EXPECT_LT(latency, 0.5);
  }
}

// The surface check must not refuse a legitimate mesh of a curved surface, where the tet
// boundary only approximates the input, coarse or fine.
TEST(Tetrahedralize, CurvedSurfacePassesTheFillCheck) {
  const SurfaceMesh sphere = test::icosphere(3);
  const double volume = signed_volume(sphere);
  ASSERT_NEAR(volume, 4.0 / 3.0 * M_PI, 0.05);
  TetrahedralizeOptions options;
  for (int target : {50, 500, 5000}) {
    options.target_tets = target;
    TetrahedralizeReport report;
    const TetMesh m = tetrahedralize(sphere, options, &report);
    // Inscribed in a convex surface: never more volume, and at most the sag of its facets less,
    // CGAL's facet-distance bound (a quarter of the size bound) times the area: 24 % at 50 tets.
    EXPECT_LE(m.total_volume(), volume * (1.0 + 1e-9)) << target;
    EXPECT_GE(m.total_volume(), volume - surface_area(sphere) * report.cell_size / 4.0) << target;
    EXPECT_LE(boundary_area(m), surface_area(sphere) * (1.0 + 1e-9)) << target;
  }
}

// A prism over the polygon `xy` (counter-clockwise), from z = 0 to `height`, outward-oriented.
// The caps are fans from vertex 0, so the polygon must be star-shaped from it.
SurfaceMesh prism(const std::vector<Eigen::Vector2d>& xy, double height, const char* name) {
  const int n = static_cast<int>(xy.size());
  SurfaceMesh s;
  s.source_name = name;
  s.vertices.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    s.vertices.row(i) << xy[i].x(), xy[i].y(), 0.0;
    s.vertices.row(n + i) << xy[i].x(), xy[i].y(), height;
  }
  std::vector<Eigen::Vector3i> f;
  for (int i = 1; i + 1 < n; ++i) {
    f.emplace_back(0, i + 1, i);
    f.emplace_back(n, n + i, n + i + 1);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    f.emplace_back(i, j, n + j);
    f.emplace_back(i, n + j, n + i);
  }
  s.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) s.faces.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return s;
}

// A thick block with a thin fin: 2V/A is set by the block, so the first size bound is far too
// coarse for the 0.04 m fin and that attempt comes out without it. The check sees this and
// re-meshes finer; when that would need far more tets than asked for it refuses, naming the
// surface and the figures. Main returned such meshes silently.
TEST(Tetrahedralize, ThinFinIsRemeshedUntilFilledOrRefused) {
  TetrahedralizeOptions options;
  options.perturb_time_limit_s = 0.5;
  options.exude_time_limit_s = 0.5;
  {
    const SurfaceMesh s = prism({{0, 0}, {2, 0}, {2, 0.1}, {1, 0.1}, {1, 1}, {0, 1}}, 1.0, "block with fin");
    options.target_tets = 2000;
    TetrahedralizeReport report;
    const TetMesh m = tetrahedralize(s, options, &report);
    EXPECT_GT(report.attempts, 1);
    EXPECT_NEAR(m.total_volume(), 1.1, 1e-12);
    EXPECT_NEAR(boundary_area(m), surface_area(s), 1e-12);
  }
  // A 0.02 m fin: at the 20° facet angle a 0.04 m fin is filled at ≈ 99K tets, inside the
  // 10 × 2000 + 1e5 allowed, so the refusal needs a fin that would take more.
  const SurfaceMesh s = prism({{0, 0}, {2, 0}, {2, 0.02}, {1, 0.02}, {1, 1}, {0, 1}}, 1.0, "block with fin");
  ASSERT_NEAR(signed_volume(s), 1.02, 1e-14);

  options.target_tets = 2000;
  try {
    tetrahedralize(s, options);
    FAIL() << "accepted";
  } catch (const NumericalFailure& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("block with fin: after 3 attempts"), std::string::npos) << what;
    // The missing part of the fin: by volume (the facet-distance bound keeps the volume
    // tolerance below the fin's deficit), or by area where that tolerance is wider.
    EXPECT_TRUE(what.find("instead of 1.02 m^3") != std::string::npos || what.find("instead of 8.04 m^2") != std::string::npos)
        << what;
    EXPECT_NE(what.find("more than 10 times the 2000 asked for"), std::string::npos) << what;
  }
}

TEST(Tetrahedralize, RefusesBadInputAndHonoursCancel) {
  TetrahedralizeOptions options;
  options.target_tets = 2000;
  SurfaceMesh open = make_tile_surface({1, 1, 1});
  open.faces.conservativeResize(11, 3);
  EXPECT_THROW(tetrahedralize(open, options), InvalidInput);
  SurfaceMesh inside_out = make_tile_surface({1, 1, 1});
  inside_out.faces.col(1).swap(inside_out.faces.col(2));
  EXPECT_THROW(tetrahedralize(inside_out, options), InvalidInput);
  TetrahedralizeOptions bad = options;
  bad.facet_angle_deg = 40;
  EXPECT_THROW(tetrahedralize(make_tile_surface({1, 1, 1}), bad), InvalidInput);
  CancelToken cancel;
  cancel.cancel();
  EXPECT_THROW(tetrahedralize(make_tile_surface({1, 1, 1}), options, nullptr, nullptr, &cancel), Cancelled);
}


// Issue 9: the count lands within count_tolerance of the request and perturbation + exudation
// reach 10° on the thin tile and on two curved bodies, a bulky one (sphere) and one as thin as
// the tile (curved shell). The 7K tile used to take 2.5 s: a first attempt, optimised and then
// discarded for a count 26 % high, and a perturber stuck on tets spanning the plate. The same
// thin request twice gives the same bytes (the accepted refinement is optimised from a reseeded
// generator, whatever attempts came before).
TEST(Tetrahedralize, CountAndQualityOnThinAndCurvedBodies) {
  struct Case {
    SurfaceMesh surface;
    int target;
  };
  const std::vector<Case> cases = {{make_tile_surface({1.0, 1.0, 0.05}), 7000},
                                   {make_tile_surface({1.0, 1.0, 0.05}), 24000},
                                   {test::icosphere(3), 7000},
                                   {test::icosphere(3), 24000},
                                   {test::curved_shell(), 7000},
                                   {test::curved_shell(), 24000}};
  // The shell holds the tile's 0.05 m³, less its chords' 4e-5 (curved_shapes.hpp).
  ASSERT_NEAR(signed_volume(test::curved_shell()), 0.05, 0.05 * 1e-4);
  for (const Case& c : cases) {
    TetrahedralizeOptions options;
    options.target_tets = c.target;
    TetrahedralizeReport report;
    const TetMesh m = tetrahedralize(c.surface, options, &report);
    const std::string what = c.surface.source_name + " at " + std::to_string(c.target);
    EXPECT_LE(std::abs(static_cast<double>(m.tet_count()) / c.target - 1.0), options.count_tolerance) << what;
    EXPECT_GE(report.quality.min_dihedral_deg, 10.0) << what;
    EXPECT_TRUE(report.warnings.empty()) << what;
    EXPECT_EQ(m.component_count(), 1) << what;
  }
  TetrahedralizeOptions options;
  options.target_tets = 7000;
  const TetMesh a = tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options);
  const TetMesh b = tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options);
  EXPECT_TRUE(a.nodes() == b.nodes());  // bitwise
  EXPECT_TRUE(a.tets() == b.tets());
}

}  // namespace
}  // namespace fissure
