#include "fissure/fem/assembly.hpp"

#include "fissure/base/parallel.hpp"
#include "fissure/base/thread_count.hpp"

#include <algorithm>

namespace fissure {

StiffnessPattern::StiffnessPattern(const TetMesh& mesh) : m_tet_nodes(mesh.tets()) {
  const int n_nodes = mesh.node_count();
  const int n_tets = mesh.tet_count();

  // Node adjacency (including the node itself) as CSR: count, fill, sort, deduplicate.
  std::vector<int> start(static_cast<std::size_t>(n_nodes) + 1, 0);
  for (int t = 0; t < n_tets; ++t)
    for (int b = 0; b < 4; ++b) start[static_cast<std::size_t>(m_tet_nodes(t, b)) + 1] += 4;
  for (int v = 0; v < n_nodes; ++v) start[v + 1] += start[v];
  std::vector<int> adjacency(static_cast<std::size_t>(start[n_nodes]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int t = 0; t < n_tets; ++t)
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a) adjacency[fill[m_tet_nodes(t, b)]++] = m_tet_nodes(t, a);
  std::vector<int> degree(static_cast<std::size_t>(n_nodes));
  for (int v = 0; v < n_nodes; ++v) {
    auto first = adjacency.begin() + start[v];
    auto last = adjacency.begin() + start[v + 1];
    std::sort(first, last);
    degree[v] = static_cast<int>(std::unique(first, last) - first);
  }

  // CSC pattern of the 3n×3n matrix: column 3b+j holds rows 3a+i for every neighbour a of b.
  const int dofs = 3 * n_nodes;
  m_column_start.assign(static_cast<std::size_t>(dofs) + 1, 0);
  for (int b = 0; b < n_nodes; ++b)
    for (int j = 0; j < 3; ++j) m_column_start[3 * b + j + 1] = 3 * degree[b];
  for (int c = 0; c < dofs; ++c) m_column_start[c + 1] += m_column_start[c];
  m_row_index.resize(static_cast<std::size_t>(m_column_start[dofs]));
  for (int b = 0; b < n_nodes; ++b) {
    for (int j = 0; j < 3; ++j) {
      int k = m_column_start[3 * b + j];
      for (int r = 0; r < degree[b]; ++r)
        for (int i = 0; i < 3; ++i) m_row_index[k++] = 3 * adjacency[start[b] + r] + i;
    }
  }

  // Rank of each local node a in the neighbour list of local node b, per tet.
  m_rank.resize(n_tets, 16);
  for (int t = 0; t < n_tets; ++t) {
    for (int b = 0; b < 4; ++b) {
      const int vb = m_tet_nodes(t, b);
      const int* first = adjacency.data() + start[vb];
      const int* last = first + degree[vb];
      for (int a = 0; a < 4; ++a) {
        m_rank(t, 4 * b + a) = static_cast<int>(std::lower_bound(first, last, m_tet_nodes(t, a)) - first);
      }
    }
  }
}

SparseMatrixD StiffnessPattern::empty_matrix() const {
  const int dofs = dof_count();
  const int nnz = m_column_start.back();
  SparseMatrixD m(dofs, dofs);
  m.resizeNonZeros(nnz);
  std::copy(m_column_start.begin(), m_column_start.end(), m.outerIndexPtr());
  std::copy(m_row_index.begin(), m_row_index.end(), m.innerIndexPtr());
  std::fill(m.valuePtr(), m.valuePtr() + nnz, 0.0);
  return m;
}

SparseMatrixD assemble_stiffness(const TetMesh& mesh, const TetGradients& gradients,
                                 const ElasticMaterial& material, const StiffnessPattern& pattern,
                                 int threads) {
  const int n_tets = mesh.tet_count();
  const double lambda = material.lame_lambda();
  const double mu = material.shear_modulus();

  // Element blocks: K_ab = V (λ g_a g_bᵀ + μ g_b g_aᵀ + μ (g_a·g_b) I), stored per tet as 16
  // blocks of 9 (block (a, b) column-major), computed (in parallel) for a batch of tets and then
  // scattered into K in tet order: the summation order is fixed, hence the bits at any thread
  // count. A buffer for every tet (144 doubles each, 65 MB at 54K) came from mmap and was
  // re-faulted page by page on every call, at ~10 µs a page several times the arithmetic
  // (issue 9). On one thread a batch of 64 tets (74 KB) stays below malloc's mmap threshold and in
  // L2; on more, batches of 1,024 tets per thread keep thread start-up small against the work.
  const int workers = std::max(1, std::min(threads, thread_count()));
  constexpr int kChunk = 256;  // tets per parallel work item
  const int batch_size = workers == 1 ? 64 : 4 * kChunk * workers;
  std::vector<double> blocks(static_cast<std::size_t>(std::min(n_tets, batch_size)) * 144);
  SparseMatrixD k = pattern.empty_matrix();
  double* values = k.valuePtr();
  for (int batch = 0; batch < n_tets; batch += batch_size) {
    const int batch_end = std::min(n_tets, batch + batch_size);
    const std::size_t chunks = static_cast<std::size_t>(batch_end - batch + kChunk - 1) / kChunk;
    parallel_for(chunks, threads, [&](std::size_t c) {
      const int begin = batch + static_cast<int>(c) * kChunk;
      const int end = std::min(batch_end, begin + kChunk);
      for (int t = begin; t < end; ++t) {
        Eigen::Vector3d g[4];
        for (int a = 0; a < 4; ++a) g[a] = gradients.gradient(t, a);
        const double v = gradients.volumes[t];
        double* out = blocks.data() + static_cast<std::size_t>(t - batch) * 144;
        for (int b = 0; b < 4; ++b) {
          for (int a = 0; a < 4; ++a) {
            const double dot = mu * g[a].dot(g[b]);
            double* blk = out + 9 * (4 * b + a);
            for (int j = 0; j < 3; ++j)
              for (int i = 0; i < 3; ++i)
                blk[3 * j + i] = v * (lambda * g[a][i] * g[b][j] + mu * g[b][i] * g[a][j] +
                                      (i == j ? dot : 0.0));
          }
        }
      }
    });
    for (int t = batch; t < batch_end; ++t) {
      const double* blk = blocks.data() + static_cast<std::size_t>(t - batch) * 144;
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a, blk += 9)
          for (int j = 0; j < 3; ++j) {
            double* col = values + pattern.block_slot(t, a, b, j);
            col[0] += blk[3 * j];
            col[1] += blk[3 * j + 1];
            col[2] += blk[3 * j + 2];
          }
    }
  }
  return k;
}

Eigen::VectorXd lumped_mass(const TetMesh& mesh, double density) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh.node_count()));
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const double share = density * mesh.volumes()[t] / 4.0;
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) m[3 * mesh.tets()(t, a) + i] += share;
  }
  return m;
}

SparseMatrixD consistent_mass(const TetMesh& mesh, double density, const StiffnessPattern& pattern) {
  SparseMatrixD m = pattern.empty_matrix();
  double* values = m.valuePtr();
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const double base = density * mesh.volumes()[t] / 20.0;
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a) {
        const double mab = a == b ? 2.0 * base : base;
        for (int j = 0; j < 3; ++j) values[pattern.block_slot(t, a, b, j) + j] += mab;
      }
  }
  return m;
}

}  // namespace fissure
