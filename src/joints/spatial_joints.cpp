#include "alphaflex/joints/spatial_joints.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace alphaflex {

namespace {

const char* label(MarkerVector u) {
  static const char* const names[] = {"a1", "a2", "a3", "b1", "b2", "b3", "d", "e_x", "e_y", "e_z"};
  return names[static_cast<int>(u)];
}
bool is_world(MarkerVector u) { return u >= MarkerVector::e_x; }
int world_index(MarkerVector u) { return static_cast<int>(u) - static_cast<int>(MarkerVector::e_x); }
unsigned bit(MarkerVector u) { return 1u << static_cast<int>(u); }

/// The drivers, equations of the same form with a weight that depends on time (the one special
/// term): angle a1·(cos φ b2 − sin φ b1) = cos φ (a1·b2) + sin φ (−a1·b1); displacement −b3·d − u(t).
struct DriverEquations {
  SpatialJointEquation angle_cos = dot(MarkerVector::a1, MarkerVector::b2);
  SpatialJointEquation angle_sin = -1.0 * dot(MarkerVector::a1, MarkerVector::b1);
  SpatialJointEquation displacement = -1.0 * dot(MarkerVector::b3, MarkerVector::d);
};
const DriverEquations& drivers() {
  static const DriverEquations d;
  return d;
}

}  // namespace

SpatialJointKind SpatialJointKind::make(std::string name, std::string doc, std::vector<SpatialJointEquation> equations,
                                        unsigned keys, unsigned drivers) {
  SpatialJointKind k;
  k.name = std::move(name);
  k.doc = std::move(doc);
  k.equations = std::move(equations);
  k.needs_axis = keys & axis;
  k.needs_axis2 = keys & axis2;
  k.takes_reference = keys & reference;
  k.angle_driver = drivers & angle;
  k.displacement_driver = drivers & displacement;
  k.num_equations = static_cast<int>(k.equations.size());
  for (const SpatialJointEquation& e : k.equations) {
    if (e.terms.empty()) throw std::logic_error("spatial joint '" + k.name + "': an equation without terms");
    for (const SpatialJointTerm& t : e.terms)
      if (is_world(t.u) && is_world(t.v))
        throw std::logic_error("spatial joint '" + k.name + "': " + e.name + " is a constant");
    for (const std::string& other : k.equation_names)
      if (other == e.name) throw std::logic_error("spatial joint '" + k.name + "': two equations named " + e.name);
    k.equation_names.push_back(e.name);
  }
  return k;
}

// The joint types. Adding one is one row here: its equations (sums of dot products of the marker
// axes a1..a3 (node 1), b1..b3 (node 2 or the ground), d = p_B − p_A and the world axes e_x..e_z),
// the scene keys it reads and the drivers it takes. The scene reader, Φ and its AD derivatives, the
// closed-form K_Φ, the equation names and the tests (which iterate over this table) follow.
const std::vector<SpatialJointKind>& spatial_joint_kinds() {
  static const std::vector<SpatialJointKind> kinds = [] {
    using V = MarkerVector;
    using K = SpatialJointKind;
    const auto row = &SpatialJointKind::make;
    const V a1 = V::a1, a2 = V::a2, a3 = V::a3, b1 = V::b1, b2 = V::b2, b3 = V::b3, d = V::d;
    // p_B − p_A = 0, by components (named x, y, z).
    const SpatialJointEquation x = dot(V::e_x, d), y = dot(V::e_y, d), z = dot(V::e_z, d);
    std::vector<SpatialJointKind> rows{
        row("spherical", "ball joint: the points coincide, any rotation", {x, y, z}, K::no_keys, K::no_drivers),
        row("universal", "Cardan joint: the points coincide, rotations about a1 = axis (body 1) and b2 = axis2",
            {x, y, z, dot(a1, b2)}, K::axis | K::axis2, K::no_drivers),
        row("revolute", "hinge: rotation about the axis a3", {x, y, z, dot(a3, b1), dot(a3, b2)}, K::axis | K::reference,
            K::angle),
        row("cylindrical", "rotation about and translation along the axis a3",
            {dot(a1, d), dot(a2, d), dot(a3, b1), dot(a3, b2)}, K::axis | K::reference, K::angle | K::displacement),
        row("prismatic", "slider: translation along the axis a3",
            {dot(a1, d), dot(a2, d), dot(a3, b1), dot(a3, b2), dot(a1, b2)}, K::axis | K::reference, K::displacement),
        row("planar", "translations in the plane ⊥ a3 and rotation about a3", {dot(a3, d), dot(a3, b1), dot(a3, b2)},
            K::axis, K::no_drivers),
        row("fixed", "clamp, rigid link: no relative motion", {x, y, z, dot(a2, b3), dot(a3, b1), dot(a1, b2)},
            K::reference, K::no_drivers),
        row("point_on_line", "B's point on A's axis a3, any rotation", {dot(a1, d), dot(a2, d)}, K::axis, K::no_drivers),
        row("point_on_plane", "B's point in the plane ⊥ a3 through A's point, any rotation (shell supports)",
            {dot(a3, d)}, K::axis, K::no_drivers),
    };
    for (size_t i = 0; i < rows.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (rows[i].name == rows[j].name) throw std::logic_error("two spatial joint types named " + rows[i].name);
    return rows;
  }();
  return kinds;
}

SpatialJointEquation dot(MarkerVector u, MarkerVector v) {
  SpatialJointEquation e;
  e.terms.push_back({u, v, 1.0});
  if (is_world(u) && v == MarkerVector::d)
    e.name = std::string(1, "xyz"[world_index(u)]);
  else
    e.name = std::string(label(u)) + "·" + label(v);
  return e;
}

SpatialJointEquation operator+(SpatialJointEquation f, const SpatialJointEquation& g) {
  f.terms.insert(f.terms.end(), g.terms.begin(), g.terms.end());
  f.name += (g.name.rfind("−", 0) == 0 ? " − " + g.name.substr(std::string("−").size()) : " + " + g.name);
  return f;
}

SpatialJointEquation operator*(double c, SpatialJointEquation f) {
  for (SpatialJointTerm& t : f.terms) t.coefficient *= c;
  std::ostringstream os;
  if (c == -1.0)
    os << "−";
  else
    os << c << " ";
  f.name = os.str() + (f.terms.size() > 1 ? "(" + f.name + ")" : f.name);
  return f;
}

const SpatialJointKind* find_spatial_joint_kind(const std::string& name) {
  for (const SpatialJointKind& k : spatial_joint_kinds())
    if (k.name == name) return &k;
  return nullptr;
}

std::string spatial_joint_kind_names() {
  std::string s;
  for (const SpatialJointKind& k : spatial_joint_kinds()) s += (s.empty() ? "" : ", ") + k.name;
  return s;
}

namespace {
/// "a, b or c": the rows that take a driver, for the constructor's message.
std::string kinds_with(bool SpatialJointKind::*driver) {
  std::vector<std::string> names;
  for (const SpatialJointKind& k : spatial_joint_kinds())
    if (k.*driver) names.push_back(k.name);
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) s += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return s;
}
}  // namespace

SpatialJoint::SpatialJoint(std::string name, std::vector<int> nodes, const SpatialJointKind& kind, SpatialMarker a,
                           SpatialMarker b, TimeFunctionPtr angle, TimeFunctionPtr displacement)
    : Constraint(std::move(name), std::move(nodes)), kind_(&kind), a_(a), b_(b), angle_(std::move(angle)),
      displacement_(std::move(displacement)) {
  if (angle_ && !kind_->angle_driver)
    throw std::invalid_argument("an angle driver needs a " + kinds_with(&SpatialJointKind::angle_driver) + " joint");
  if (displacement_ && !kind_->displacement_driver)
    throw std::invalid_argument("a displacement driver needs a " + kinds_with(&SpatialJointKind::displacement_driver) +
                                " joint");
  size_ = kind_->num_equations + (angle_ ? 1 : 0) + (displacement_ ? 1 : 0);
  const auto use = [&](const SpatialJointEquation& e) {
    for (const SpatialJointTerm& t : e.terms) uses_ |= bit(t.u) | bit(t.v);
  };
  for (const SpatialJointEquation& e : kind_->equations) use(e);
  if (angle_) use(drivers().angle_cos), use(drivers().angle_sin);
  if (displacement_) use(drivers().displacement);
}

std::string SpatialJoint::equation_name(int k) const {
  if (k < kind_->num_equations) return kind_->equation_names[static_cast<size_t>(k)];
  return angle_ && k == kind_->num_equations ? "angle" : "displacement";
}

namespace {

/// The marker poses and d at given frames, for the AD kernel (the axes are read in place as columns).
template <class S>
struct KernelVectors {
  Pose<S> A, B;
  Vec3<S> d;

  /// f(the vector u) for a marker axis or d (not a world axis).
  template <class F>
  S with(MarkerVector u, F&& f) const {
    switch (u) {
      case MarkerVector::a1: return f(A.R.col(0));
      case MarkerVector::a2: return f(A.R.col(1));
      case MarkerVector::a3: return f(A.R.col(2));
      case MarkerVector::b1: return f(B.R.col(0));
      case MarkerVector::b2: return f(B.R.col(1));
      case MarkerVector::b3: return f(B.R.col(2));
      default: return f(d);
    }
  }

  /// u·v (with a world axis: the component of the other vector).
  S dot(MarkerVector u, MarkerVector v) const {
    if (is_world(u)) return with(v, [&](const auto& w) -> S { return w[world_index(u)]; });
    if (is_world(v)) return with(u, [&](const auto& w) -> S { return w[world_index(v)]; });
    return with(u, [&](const auto& p) -> S { return with(v, [&](const auto& r) -> S { return p.dot(r); }); });
  }

  /// The value of an equation (terms with coefficient 1 unscaled: the same bits as u·v).
  S operator()(const SpatialJointEquation& e) const {
    const auto term = [&](const SpatialJointTerm& t) -> S {
      const S v = dot(t.u, t.v);
      return t.coefficient == 1.0 ? v : S(t.coefficient * v);
    };
    S sum = term(e.terms.front());
    for (size_t i = 1; i < e.terms.size(); ++i) sum += term(e.terms[i]);
    return sum;
  }
};

}  // namespace

template <class S>
void SpatialJoint::operator()(const Pose<S>* frames, const S& t, KernelVector<S>& out) const {
  KernelVectors<S> m{a_.pose<S>(frames), b_.pose<S>(frames), Vec3<S>()};
  m.d = m.B.x - m.A.x;
  out.resize(size_);
  int k = 0;
  for (const SpatialJointEquation& e : kind_->equations) out[k++] = m(e);
  if (angle_) {
    using std::cos;
    using std::sin;
    const S phi = time_value<S>(*angle_, t);
    out[k++] = cos(phi) * m(drivers().angle_cos) + sin(phi) * m(drivers().angle_sin);  // sin(ϕ − φ(t))
  }
  if (displacement_) out[k++] = m(drivers().displacement) - time_value<S>(*displacement_, t);  // (p_A − p_B)·b3 = u(t)
}

namespace {

// Closed-form geometric stiffness. Every equation of a spatial joint is a sum of dot products u·v of
// vectors among: marker axes R_f w (w a fixed axis in node f's frame), marker points x_f + R_f s,
// d = p_B − p_A, and fixed world vectors; and every such vector is affine in the entries of (x_f, R_f).
// With the perturbations of model/spatial_kernel.hpp, (x + δx' + δx, R(I + δθ'^)(I + δθ^)), the
// mixed derivative of a dot product is
//     ∂²(u·v)/∂δ'_j∂δ_i = u_ji·v + u_i·v_j + u_j·v_i + u·v_ji,
// first derivatives of R_f w being R_f (e_m × w) = −R_f ŵ e_m, and the only second derivatives
// those of R_f w within one node's rotations: ∂²/∂δθ'_p∂δθ_m R_f w = R_f ê_p ê_m w
// = R_f (e_m w_p − δ_mp w), so that v·u_ji over that block is (R_fᵀv) wᵀ − (R_fᵀv · w) I
// (row m: inner, column p: outer). The same bits of K_Φ as nested AD up to round-off (tested
// against kernel_second and finite differences), at a small fraction of its cost.
struct JointVector {
  Eigen::Vector3d value;
  Eigen::Matrix<double, 3, 12> d1;  // ∂/∂δ, 6 per node; set only if `varies`
  struct Rotating {
    int node;
    Eigen::Vector3d w;  // in the node's frame
    double sign;
  };
  std::array<Rotating, 2> parts;
  int nparts = 0;
  bool varies = false;  // d1 ≠ 0 (false: a fixed world vector, on the ground)
};

/// u = R_f w: axis `k` of marker m (a fixed world vector on the ground), set in place.
void set_marker_axis(JointVector& u, const SpatialMarker& m, int k, const Pose<double>* frames) {
  if (m.slot < 0) {
    u.value = m.rotation.col(k);
    return;
  }
  const Eigen::Matrix3d& R = frames[m.slot].R;
  const Eigen::Vector3d w = m.rotation.col(k);
  u.value = R * w;
  u.d1.setZero();
  u.d1.block<3, 3>(0, 6 * m.slot + 3) = -R * hat<double>(w);
  u.parts[0] = {m.slot, w, 1.0};
  u.nparts = 1;
  u.varies = true;
}

/// d = p_B − p_A, p = x_f + R_f s the point of a marker (s in the world on the ground), set in place.
void set_marker_difference(JointVector& d, const SpatialMarker& a, const SpatialMarker& b,
                           const Pose<double>* frames) {
  const auto point = [&](const SpatialMarker& m) -> Eigen::Vector3d {
    if (m.slot < 0) return m.position;
    return frames[m.slot].x + frames[m.slot].R * m.position;
  };
  d.value = point(b) - point(a);
  d.d1.setZero();
  for (const SpatialMarker* m : {&b, &a}) {
    if (m->slot < 0) continue;
    const double sign = m == &b ? 1.0 : -1.0;
    const Eigen::Matrix3d& R = frames[m->slot].R;
    d.d1.block<3, 3>(0, 6 * m->slot) = sign * Eigen::Matrix3d::Identity();
    d.d1.block<3, 3>(0, 6 * m->slot + 3) = sign * (-R * hat<double>(m->position));
    d.parts[static_cast<size_t>(d.nparts++)] = {m->slot, m->position, sign};
    d.varies = true;
  }
}

/// The fixed world axes e_x, e_y, e_z.
const std::array<JointVector, 3>& world_axes() {
  static const std::array<JointVector, 3> e = [] {
    std::array<JointVector, 3> v;
    for (int i = 0; i < 3; ++i) v[static_cast<size_t>(i)].value = Eigen::Vector3d::Unit(i);
    return v;
  }();
  return e;
}

/// H += c ∂²(u·v)/∂δ'∂δ on the n unknowns of the joint's nodes.
void add_dot_second(double c, const JointVector& u, const JointVector& v, const Pose<double>* frames, int n,
                    Eigen::MatrixXd& H) {
  if (c == 0.0) return;
  if (u.varies && v.varies) {  // (with a fixed vector, u_i·v_j + u_j·v_i = 0)
    const auto U = u.d1.leftCols(n), V = v.d1.leftCols(n);
    H.noalias() += c * (U.transpose() * V + V.transpose() * U);
  }
  auto rotating = [&](const JointVector& a, const JointVector& other) {
    for (int i = 0; i < a.nparts; ++i) {
      const JointVector::Rotating& r = a.parts[static_cast<size_t>(i)];
      const Eigen::Vector3d g = frames[r.node].R.transpose() * other.value;
      H.block<3, 3>(6 * r.node + 3, 6 * r.node + 3).noalias() +=
          (c * r.sign) * (g * r.w.transpose() - g.dot(r.w) * Eigen::Matrix3d::Identity());
    }
  };
  rotating(u, v);
  rotating(v, u);
}

/// H += weight ∂²(equation)/∂δ'∂δ, the vectors indexed by MarkerVector.
void add_equation_second(double weight, const SpatialJointEquation& e, const JointVector* const* vectors,
                         const Pose<double>* frames, int n, Eigen::MatrixXd& H) {
  for (const SpatialJointTerm& t : e.terms)
    add_dot_second(t.coefficient * weight, *vectors[static_cast<int>(t.u)], *vectors[static_cast<int>(t.v)], frames, n, H);
}

/// row += c ∂(u·v)/∂δ = c (vᵀu_δ + uᵀv_δ) on the n unknowns of the joint's nodes.
template <class Row>
void add_dot_first(double c, const JointVector& u, const JointVector& v, int n, Row&& row) {
  if (c == 0.0) return;
  if (u.varies) row.noalias() += (c * v.value).transpose() * u.d1.leftCols(n);
  if (v.varies) row.noalias() += (c * u.value).transpose() * v.d1.leftCols(n);
}

/// The vectors the equations use, by MarkerVector (a1..b3, d: only those in `uses` are set; world
/// axes: fixed), at the given frames.
struct JointVectors {
  std::array<JointVector, 7> m;
  const JointVector* v[10];
  JointVectors(unsigned uses, const SpatialMarker& a, const SpatialMarker& b, const Pose<double>* frames) {
    for (int i = 0; i < 3; ++i) {
      if (uses & bit(MarkerVector(i))) set_marker_axis(m[static_cast<size_t>(i)], a, i, frames);
      if (uses & bit(MarkerVector(3 + i))) set_marker_axis(m[static_cast<size_t>(3 + i)], b, i, frames);
    }
    if (uses & bit(MarkerVector::d)) set_marker_difference(m[6], a, b, frames);
    const std::array<JointVector, 3>& e_xyz = world_axes();
    for (int i = 0; i < 7; ++i) v[i] = &m[static_cast<size_t>(i)];
    for (int i = 0; i < 3; ++i) v[7 + i] = &e_xyz[static_cast<size_t>(i)];
  }
  JointVectors(const JointVectors&) = delete;
  JointVectors& operator=(const JointVectors&) = delete;
};

/// row += weight ∂(equation)/∂δ.
template <class Row>
void add_equation_first(double weight, const SpatialJointEquation& e, const JointVectors& vs, int n, Row&& row) {
  for (const SpatialJointTerm& t : e.terms)
    add_dot_first(t.coefficient * weight, *vs.v[static_cast<int>(t.u)], *vs.v[static_cast<int>(t.v)], n, row);
}

}  // namespace

void SpatialJoint::geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                                       Eigen::MatrixXd& k) const {
  const int nf = kernel_detail::frames_in(q);
  const int n = 6 * nf;
  const kernel_detail::Poses p = kernel_detail::poses(q, nf);
  const Pose<double>* frames = p.data();
  k.setZero(n, n);
  const DriverEquations& dr = drivers();
  const JointVectors vs(uses_, a_, b_, frames);
  const JointVector* const* v = vs.v;
  int e = 0;  // equation, in the order of operator()
  for (const SpatialJointEquation& eq : kind_->equations) add_equation_second(lambda[e++], eq, v, frames, n, k);
  if (angle_) {  // cos φ (a1·b2) + sin φ (−a1·b1)
    const double phi = angle_->value(t);
    add_equation_second(std::cos(phi) * lambda[e], dr.angle_cos, v, frames, n, k);
    add_equation_second(std::sin(phi) * lambda[e], dr.angle_sin, v, frames, n, k);
    ++e;
  }
  if (displacement_) add_equation_second(lambda[e++], dr.displacement, v, frames, n, k);  // −b3·d − u(t)
}

void SpatialJoint::geometric_stiffness_by_ad(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                                             Eigen::MatrixXd& k) const {
  kernel_second(*this, q, t, lambda, k);
}

void SpatialJoint::evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  // Φ by the kernel in doubles (the bits of the AD path's value part); Φ_q in closed form from the
  // first derivatives of the marker vectors (JointVector::d1, the same as K_Φ's above), ~4× cheaper
  // than forward AD over the 12 increments, which it equals to round-off (test_spatial_tangents.cpp).
  const int nf = kernel_detail::frames_in(q);
  const int n = 6 * nf;
  const kernel_detail::Poses p = kernel_detail::poses(q, nf);
  KernelVector<double> r;
  (*this)(p.data(), t, r);
  phi = r;
  phi_q.setZero(size_, n);
  const JointVectors vs(uses_, a_, b_, p.data());
  int e = 0;  // equation, in the order of operator()
  for (const SpatialJointEquation& eq : kind_->equations) add_equation_first(1.0, eq, vs, n, phi_q.row(e++));
  if (angle_) {  // cos φ (a1·b2) + sin φ (−a1·b1)
    const double angle = angle_->value(t);
    add_equation_first(std::cos(angle), drivers().angle_cos, vs, n, phi_q.row(e));
    add_equation_first(std::sin(angle), drivers().angle_sin, vs, n, phi_q.row(e));
    ++e;
  }
  if (displacement_) add_equation_first(1.0, drivers().displacement, vs, n, phi_q.row(e++));  // −b3·d − u(t)
}

void SpatialJoint::evaluate_by_ad(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  kernel_jacobian(*this, q, t, phi, phi_q);
}

void SpatialJoint::time_derivative(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi_t) const {
  if (!angle_ && !displacement_) {
    phi_t = Eigen::VectorXd::Zero(size_);
    return;
  }
  Eigen::VectorXd second;
  kernel_along_motion(*this, q, Eigen::VectorXd::Zero(q.size() / 7 * 6), t, 1.0, phi_t, second);
}

void SpatialJoint::acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                                     Eigen::VectorXd& c) const {
  Eigen::VectorXd first;
  kernel_along_motion(*this, q, v, t, 1.0, first, c);
}

JointReaction SpatialJoint::reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const {
  Eigen::VectorXd phi;
  Eigen::MatrixXd J;
  evaluate(q, t, phi, J);
  const Eigen::VectorXd g = -J.transpose() * lambda;  // generalized force of the joint on its nodes
  const Pose<double> node1 = pose_of(q.data());
  const Pose<double> frames[2] = {node1, q.size() >= 14 ? pose_of(q.data() + 7) : node1};
  const Pose<double> A = a_.pose<double>(frames);
  JointReaction r;
  r.location = A.x;
  r.force = g.segment<3>(0);
  r.moment = node1.R * g.segment<3>(3) - (A.x - node1.x).cross(r.force);
  r.frame = A.R;
  return r;
}

template void SpatialJoint::operator()(const Pose<double>*, const double&, KernelVector<double>&) const;

}  // namespace alphaflex
