#include "results_layout.hpp"

#include <Eigen/SVD>
#include <algorithm>

namespace alphaflex::io_detail {

NodeLayout node_layout(const Model& global, const std::vector<ElementGrid>& grids) {
  NodeLayout L;
  const size_t nn = global.nodes().size();
  L.node_block.assign(nn, -1);
  std::vector<char> drawn(nn, 0);
  for (const ElementGrid& g : grids)
    for (int e : g.elements) {
      const Element& el = *global.elements()[static_cast<size_t>(e)];
      const std::string block = el.name().substr(0, el.name().find('['));
      auto b = std::find(L.blocks.begin(), L.blocks.end(), block);
      if (b == L.blocks.end()) b = L.blocks.insert(L.blocks.end(), block);
      for (int n : el.nodes()) {
        drawn[static_cast<size_t>(n)] = 1;
        // A node shared by two blocks (a beam welded to a plate) belongs to the first.
        if (L.node_block[static_cast<size_t>(n)] < 0) L.node_block[static_cast<size_t>(n)] = static_cast<int>(b - L.blocks.begin());
      }
    }
  L.body_row.assign(nn, -1);
  for (size_t n = 0; n < nn; ++n)
    if (!drawn[n]) {
      L.body_row[n] = static_cast<int>(L.bodies.size());
      L.bodies.push_back(static_cast<int>(n));
    }
  const auto& joints = global.constraints();
  L.link_row.assign(joints.size(), -1);
  for (size_t c = 0; c < joints.size(); ++c) {
    const auto& nodes = joints[c]->nodes();
    if (std::any_of(nodes.begin(), nodes.end(), [&](int n) { return L.body_row[static_cast<size_t>(n)] >= 0; })) {
      L.link_row[c] = static_cast<int>(L.links.size());
      L.links.push_back(static_cast<int>(c));
    }
  }
  L.shapes = shape_layout(global);
  L.reduced = reduced_layout(global);
  return L;
}

std::vector<double> elastic_displacements(const Subdomain& sub, const NodeLayout& L, const std::vector<double>& pos,
                                          const std::vector<double>& disp) {
  const size_t nb = L.blocks.size(), nn = pos.size() / 3;
  std::vector<double> out(3 * nn, 0.0);
  if (nb == 0) return out;
  // Per block: node count, Σ X, Σ x, Σ X xᵀ (1 + 3 + 3 + 9 numbers), summed over the ranks' owned
  // nodes; H = Σ X xᵀ − n c_X cᵀ follows from them.
  std::vector<double> sums(16 * nb, 0.0);
  auto block_of = [&](size_t i) { return L.node_block[static_cast<size_t>(sub.global_node(static_cast<int>(i)))]; };
  for (size_t i = 0; i < nn; ++i) {
    const int b = block_of(i);
    if (b < 0) continue;
    double* s = &sums[16 * static_cast<size_t>(b)];
    const Eigen::Vector3d x(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    const Eigen::Vector3d X = x - Eigen::Vector3d(disp[3 * i], disp[3 * i + 1], disp[3 * i + 2]);
    s[0] += 1.0;
    for (int k = 0; k < 3; ++k) {
      s[1 + k] += X[k];
      s[4 + k] += x[k];
      for (int l = 0; l < 3; ++l) s[7 + 3 * k + l] += X[k] * x[l];
    }
  }
  sub.sum(sums);
  std::vector<Eigen::Matrix3d> R(nb, Eigen::Matrix3d::Identity());
  std::vector<Eigen::Vector3d> cX(nb, Eigen::Vector3d::Zero()), cx(nb, Eigen::Vector3d::Zero());
  for (size_t b = 0; b < nb; ++b) {
    const double* s = &sums[16 * b];
    if (!(s[0] > 0.0)) continue;
    cX[b] = Eigen::Vector3d(s[1], s[2], s[3]) / s[0];
    cx[b] = Eigen::Vector3d(s[4], s[5], s[6]) / s[0];
    Eigen::Matrix3d H;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) H(k, l) = s[7 + 3 * k + l] - s[0] * cX[b][k] * cx[b][l];
    // Kabsch: H = U Σ Vᵀ, R = V diag(1, 1, det(V Uᵀ)) Uᵀ (a proper rotation even when the best
    // orthogonal fit would be a reflection, e.g. for a flat block whose normal is undetermined).
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
    R[b] = svd.matrixV() * D * svd.matrixU().transpose();
  }
  for (size_t i = 0; i < nn; ++i) {
    const int b = block_of(i);
    if (b < 0) continue;
    const size_t k = static_cast<size_t>(b);
    const Eigen::Vector3d x(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    const Eigen::Vector3d X = x - Eigen::Vector3d(disp[3 * i], disp[3 * i + 1], disp[3 * i + 2]);
    const Eigen::Vector3d u = x - (cx[k] + R[k] * (X - cX[k]));
    for (int c = 0; c < 3; ++c) out[3 * i + static_cast<size_t>(c)] = u[c];
  }
  return out;
}

}  // namespace alphaflex::io_detail
