#include "supernodal_solve.hpp"

#include <algorithm>
#include <memory>

namespace fissure {
namespace {

// Right-hand sides per pass: the 8 doubles of one row fill an AVX-512 register (two AVX2 ones).
// GCC's vector extension says so to the compiler, which left to itself vectorised the loops
// across the four accumulators instead and spilled (3× slower).
constexpr int kWidth = 8;
typedef double Row __attribute__((vector_size(kWidth * sizeof(double))));

// The supernodal factor as CHOLMOD stores it: supernode s holds columns super[s] … super[s+1]−1;
// its row indices are rows[pi[s] … pi[s+1]−1], the first of them its own columns; its values are
// the nsrow × nscol column-major block at values + px[s], lower triangle on top.
struct Supernodes {
  const int* super;
  const int* pi;
  const int* px;
  const int* rows;
  const double* values;
  long count;
};

struct Supernode {
  int first;  // first column
  int cols;   // nscol
  int rows;   // nsrow
  const int* row_index;
  const double* l;  // column j at l + j·rows
};

Supernode supernode(const Supernodes& f, long s) {
  return {f.super[s], f.super[s + 1] - f.super[s], f.pi[s + 1] - f.pi[s], f.rows + f.pi[s], f.values + f.px[s]};
}

// Rows of the system a supernode's rows map to: its own columns (contiguous) or, below them,
// its row indices.
struct Own {
  int operator()(int i) const { return i; }
};
struct Indexed {
  const int* rows;
  int operator()(int i) const { return rows[i]; }
};

// dest[row(i)] −= Σ_{j ∈ [j0, j1)} L(i, j) src[j] for i ∈ [i0, i1). Eight rows at a time: eight
// independent accumulators cover the FMA latency, and each src row is loaded once for eight.
template <class Row_of>
void subtract_product(const double* l, long ld, int i0, int i1, int j0, int j1, const Row* src, Row* dest,
                      Row_of row) {
  int i = i0;
  for (; i + 8 <= i1; i += 8) {
    Row a0 = {}, a1 = {}, a2 = {}, a3 = {}, a4 = {}, a5 = {}, a6 = {}, a7 = {};
    for (int j = j0; j < j1; ++j) {
      const double* lj = l + j * ld + i;
      const Row v = src[j];
      a0 += lj[0] * v;
      a1 += lj[1] * v;
      a2 += lj[2] * v;
      a3 += lj[3] * v;
      a4 += lj[4] * v;
      a5 += lj[5] * v;
      a6 += lj[6] * v;
      a7 += lj[7] * v;
    }
    dest[row(i)] -= a0;
    dest[row(i + 1)] -= a1;
    dest[row(i + 2)] -= a2;
    dest[row(i + 3)] -= a3;
    dest[row(i + 4)] -= a4;
    dest[row(i + 5)] -= a5;
    dest[row(i + 6)] -= a6;
    dest[row(i + 7)] -= a7;
  }
  for (; i < i1; ++i) {
    Row a = {};
    for (int j = j0; j < j1; ++j) a += l[j * ld + i] * src[j];
    dest[row(i)] -= a;
  }
}

// dest[j] −= Σ_{i ∈ [i0, i1)} L(i, j) src[row(i)] for j ∈ [j0, j1): the transposed product, eight
// columns at a time for the same reasons (each src row gathered once for eight).
template <class Row_of>
void subtract_transposed_product(const double* l, long ld, int i0, int i1, int j0, int j1, const Row* src, Row* dest,
                                 Row_of row) {
  int j = j0;
  for (; j + 8 <= j1; j += 8) {
    Row a0 = {}, a1 = {}, a2 = {}, a3 = {}, a4 = {}, a5 = {}, a6 = {}, a7 = {};
    const double* lj = l + j * ld;
    for (int i = i0; i < i1; ++i) {
      const Row v = src[row(i)];
      a0 += lj[i] * v;
      a1 += lj[ld + i] * v;
      a2 += lj[2 * ld + i] * v;
      a3 += lj[3 * ld + i] * v;
      a4 += lj[4 * ld + i] * v;
      a5 += lj[5 * ld + i] * v;
      a6 += lj[6 * ld + i] * v;
      a7 += lj[7 * ld + i] * v;
    }
    dest[j] -= a0;
    dest[j + 1] -= a1;
    dest[j + 2] -= a2;
    dest[j + 3] -= a3;
    dest[j + 4] -= a4;
    dest[j + 5] -= a5;
    dest[j + 6] -= a6;
    dest[j + 7] -= a7;
  }
  for (; j < j1; ++j) {
    Row a = {};
    for (int i = i0; i < i1; ++i) a += l[j * ld + i] * src[row(i)];
    dest[j] -= a;
  }
}

// Supernodes' diagonal triangles are solved in panels of this many columns: inside a panel value
// by value (each waits on the last), the rest of the triangle by the products above.
constexpr int kPanel = 8;

// L y = y, y: one Row per row of the system.
void forward(const Supernodes& f, Row* y) {
  for (long s = 0; s < f.count; ++s) {
    const Supernode sn = supernode(f, s);
    Row* ys = y + sn.first;
    for (int jb = 0; jb < sn.cols; jb += kPanel) {
      const int je = std::min(jb + kPanel, sn.cols);
      // Multiplying by the pivot's reciprocal keeps the division (tens of cycles) off the chain
      // from one value to the next, as dtrsm does.
      for (int j = jb; j < je; ++j) {
        const double* lj = sn.l + static_cast<long>(j) * sn.rows;
        const Row yj = ys[j] * (1.0 / lj[j]);
        ys[j] = yj;
        for (int i = j + 1; i < je; ++i) ys[i] -= lj[i] * yj;
      }
      subtract_product(sn.l, sn.rows, je, sn.cols, jb, je, ys, ys, Own{});
    }
    subtract_product(sn.l, sn.rows, sn.cols, sn.rows, 0, sn.cols, ys, y, Indexed{sn.row_index});
  }
}

// Lᵀ y = y, supernodes in reverse order.
void backward(const Supernodes& f, Row* y) {
  for (long s = f.count - 1; s >= 0; --s) {
    const Supernode sn = supernode(f, s);
    Row* ys = y + sn.first;
    subtract_transposed_product(sn.l, sn.rows, sn.cols, sn.rows, 0, sn.cols, y, ys, Indexed{sn.row_index});
    for (int jb = (sn.cols - 1) / kPanel * kPanel; jb >= 0; jb -= kPanel) {
      const int je = std::min(jb + kPanel, sn.cols);
      subtract_transposed_product(sn.l, sn.rows, je, sn.cols, jb, je, ys, ys, Own{});
      // Last row first, each solved value subtracted at once from the rows above it (row i of
      // L11, read across the panel's columns).
      for (int i = je - 1; i >= jb; --i) {
        const double* li = sn.l + i;
        const Row yi = ys[i] * (1.0 / li[static_cast<long>(i) * sn.rows]);
        ys[i] = yi;
        for (int j = jb; j < i; ++j) ys[j] -= li[static_cast<long>(j) * sn.rows] * yi;
      }
    }
  }
}

}  // namespace

void supernodal_block_solve(const cholmod_factor& factor, const Eigen::Ref<const Eigen::MatrixXd>& b,
                            Eigen::Ref<Eigen::MatrixXd> x) {
  const long n = static_cast<long>(factor.n);
  const Supernodes f{static_cast<const int*>(factor.super), static_cast<const int*>(factor.pi),
                     static_cast<const int*>(factor.px),    static_cast<const int*>(factor.s),
                     static_cast<const double*>(factor.x),  static_cast<long>(factor.nsuper)};
  const int* perm = static_cast<const int*>(factor.Perm);  // L Lᵀ = P A Pᵀ, row i of P A is row perm[i] of A
  // Rows of 64 bytes, each a cache line.
  const std::unique_ptr<Row[]> y(new Row[static_cast<std::size_t>(n)]);
  for (Eigen::Index c0 = 0; c0 < b.cols(); c0 += kWidth) {
    const int width = static_cast<int>(std::min<Eigen::Index>(kWidth, b.cols() - c0));
    // y = P b, interleaved; columns beyond b's are zero (and cost a pass of arithmetic).
    for (long i = 0; i < n; ++i) {
      const long from = perm ? perm[i] : i;
      Row& yi = y[static_cast<std::size_t>(i)];
      yi = Row{};
      for (int w = 0; w < width; ++w) yi[w] = b(from, c0 + w);
    }
    forward(f, y.get());
    backward(f, y.get());
    for (long i = 0; i < n; ++i) {
      const long to = perm ? perm[i] : i;
      const Row& yi = y[static_cast<std::size_t>(i)];
      for (int w = 0; w < width; ++w) x(to, c0 + w) = yi[w];
    }
  }
}

}  // namespace fissure
