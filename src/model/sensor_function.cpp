#include "alphaflex/model/sensor_function.hpp"

#include <array>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

std::vector<SlotOffsets> slot_offsets(const Model& model, const std::vector<int>& nodes) {
  std::vector<SlotOffsets> out;
  SlotOffsets o;
  for (int n : nodes) {
    out.push_back(o);
    o.conf += model.node(n).nconf;
    o.dof += model.node(n).ndof;
  }
  return out;
}

SensorFunction::SensorFunction(std::shared_ptr<const ExpressionFunction> f, std::vector<int> roles, std::vector<Input> inputs)
    : f_(std::move(f)), roles_(std::move(roles)), inputs_(std::move(inputs)) {
  if (f_->variables().size() != roles_.size()) throw std::logic_error("SensorFunction: one role per variable expected");
  for (int r : roles_)
    if (r >= static_cast<int>(inputs_.size())) throw std::logic_error("SensorFunction: a role names no input");
}

double SensorFunction::input(const Input& in, const LocalState& s, const std::vector<SlotOffsets>& layout, double weight,
                             Eigen::VectorXd* dq, Eigen::VectorXd* dv) const {
  if (in.expression) {
    if (!dq) return in.expression->evaluate(s, layout);
    Eigen::VectorXd gq, gv;
    const double value = in.expression->evaluate(s, layout, nullptr, &gq, &gv);
    *dq += weight * gq;
    *dv += weight * gv;
    return value;
  }
  const SlotOffsets& o = layout[static_cast<size_t>(in.slot)];
  switch (in.kind) {
    case Sensor::Kind::NodeCoordinate:
      if (dq) (*dq)[o.dof] += weight;
      return s.q[o.conf];
    case Sensor::Kind::NodeSpeed:
      if (dq) (*dv)[o.dof] += weight;
      return s.v[o.dof];
    default: break;
  }
  // Points of a spatial frame (sensor.cpp: the same values).
  const Pose<double> p = pose_of(s.q.data() + o.conf);
  const bool velocity = in.kind == Sensor::Kind::PointVelocity;
  const Eigen::Vector3d W = s.v.segment<3>(o.dof + 3);
  const Eigen::Matrix3d S = hat<double>(in.local);
  Eigen::Vector3d y = velocity ? Eigen::Vector3d(s.v.segment<3>(o.dof) + p.R * W.cross(in.local)) : Eigen::Vector3d(p.x + p.R * in.local);
  // Rows of the derivatives of the world vector (before a moving frame): A on δx (or ẋ), B on δθ, V on Ω.
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity(), B = velocity ? Eigen::Matrix3d(-p.R * hat<double>(Eigen::Vector3d(W.cross(in.local)))) : Eigen::Matrix3d(-p.R * S);
  const Eigen::Matrix3d V = -p.R * S;
  Eigen::Matrix3d Rf = Eigen::Matrix3d::Identity();
  if (in.frame_slot >= 0) {
    const SlotOffsets& of = layout[static_cast<size_t>(in.frame_slot)];
    const Pose<double> f = pose_of(s.q.data() + of.conf);
    Rf = f.R.transpose();
    y = velocity ? Eigen::Vector3d(Rf * y) : Eigen::Vector3d(Rf * (y - f.x));
    if (dq) {
      // ∂y/∂δθ_F = ŷ (y before subtracting `initial`), ∂y/∂δx_F = −R_Fᵀ (positions).
      const Eigen::Matrix3d Y = hat<double>(y);
      for (int j = 0; j < 3; ++j) (*dq)[of.dof + 3 + j] += weight * Y(in.component, j);
      if (!velocity)
        for (int j = 0; j < 3; ++j) (*dq)[of.dof + j] -= weight * Rf(in.component, j);
    }
  }
  if (dq) {
    const Eigen::RowVector3d a = Rf.row(in.component) * A, b = Rf.row(in.component) * B, w = Rf.row(in.component) * V;
    for (int j = 0; j < 3; ++j) {
      if (velocity) {
        (*dv)[o.dof + j] += weight * a[j];
        (*dv)[o.dof + 3 + j] += weight * w[j];
      } else {
        (*dq)[o.dof + j] += weight * a[j];
      }
      (*dq)[o.dof + 3 + j] += weight * b[j];
    }
  }
  if (in.kind == Sensor::Kind::PointDisplacement) y -= in.initial;
  return y[in.component];
}

double SensorFunction::evaluate(const LocalState& s, const std::vector<SlotOffsets>& layout, const double* leading,
                                Eigen::VectorXd* dq, Eigen::VectorXd* dv, double* leading_gradient) const {
  std::array<double, ExpressionFunction::kMaxVariables> x{}, g{};
  for (size_t k = 0; k < roles_.size(); ++k) {
    const int r = roles_[k];
    x[k] = r >= 0 ? input(inputs_[static_cast<size_t>(r)], s, layout, 0.0, nullptr, nullptr) : r == kTime ? s.t : leading[-2 - r];
  }
  if (!dq) return f_->value(x.data());
  const double value = f_->value(x.data(), g.data());
  dq->setZero(s.v.size());
  dv->setZero(s.v.size());
  for (size_t k = 0; k < roles_.size(); ++k) {
    const int r = roles_[k];
    if (r >= 0 && g[k] != 0.0) input(inputs_[static_cast<size_t>(r)], s, layout, g[k], dq, dv);
    else if (r < kTime) leading_gradient[-2 - r] += g[k];
  }
  return value;
}

std::shared_ptr<const SensorFunction> SensorFunction::rebased(const std::vector<int>& slot_map) const {
  std::vector<Input> inputs = inputs_;
  for (Input& in : inputs) {
    in.slot = slot_map[static_cast<size_t>(in.slot)];
    if (in.frame_slot >= 0) in.frame_slot = slot_map[static_cast<size_t>(in.frame_slot)];
    if (in.expression) in.expression = in.expression->rebased(slot_map);
  }
  return std::make_shared<SensorFunction>(f_, roles_, std::move(inputs));
}

}  // namespace alphaflex
