// Sensors in expressions (spatial): a joint motor whose torque names sensors (a PD or PID
// controller), the `expression` sensor (a function of other sensors) and the `integral` sensor
// (∫ e dt of an expression of sensors, a state: elements/sensor_feedback.hpp). Forces are read
// before sensors, so what names sensors is recorded here and completed by resolve_sensor_feedback
// once `sensors` is read; an expression sensor may name sensors listed after it, and a loop of
// expression sensors is refused at the key that closes it (integrals break loops: their value is
// a state). Where the pending items live: a registry per SceneBuilder of this thread, begun and
// resolved by io/scene.cpp (one scene is read at a time per thread). Element indices: nothing
// adds elements while `sensors` is read, so a pending motor k gets (elements after the forces) + k,
// and the expression/integral sensors follow in list order; resolve checks this.
// Keys: docs/input.md; theory: docs/theory/force_elements.md (feedback).
#include <algorithm>
#include <functional>
#include <map>
#include <memory>

#include "alphaflex/core/expression_names.hpp"

#include "alphaflex/elements/sensor_feedback.hpp"
#include "sensor_feedback.hpp"

namespace alphaflex::scene_detail {

/// What waits for the sensors: the motors, and the expression and integral sensors.
struct SensorFeedback {
  struct PendingMotor {
    std::string name;
    int psi = -1;
    YAML::Node node;
    std::string at, text;
    std::vector<std::string> leading;
  };
  struct PendingSensor {
    int index = -1;  ///< in the model's sensors
    YAML::Node node;
    std::string at;    ///< "sensors[NAME].value"
    std::string text;
    int integrator = -1;  ///< integral: its node w; −1: an expression sensor
    enum class State { pending, resolving, done } state = State::pending;
    std::shared_ptr<const SensorFunction> function;  ///< once resolved, on `nodes`
    std::vector<int> nodes;
  };
  std::vector<PendingMotor> motors;
  std::vector<PendingSensor> sensors;
};

namespace {

std::map<const SceneBuilder*, SensorFeedback>& registry() {
  thread_local std::map<const SceneBuilder*, SensorFeedback> r;
  return r;
}
SensorFeedback& feedback(const SceneBuilder& sb) { return registry()[&sb]; }

std::string kind_name(Sensor::Kind k) {
  switch (k) {
    case Sensor::Kind::PointAcceleration: return "an acceleration";
    case Sensor::Kind::JointReaction: return "a joint reaction (a multiplier, which an element cannot read)";
    case Sensor::Kind::BodyRotation: return "a body rotation";
    case Sensor::Kind::ElementOutput: return "an element output";
    case Sensor::Kind::ElementEnergy: return "an energy";
    case Sensor::Kind::JointViolation: return "a constraint violation";
    default: return "a planar sensor";
  }
}

class Builder {
 public:
  explicit Builder(SceneBuilder& sb) : sb_(sb), model_(sb.model_), rd_(sb.rd_) {}

  /// The function of `text` (variables: `leading`, t, then the sensors it names) on `nodes`, to
  /// which the nodes it reads are added. `chain`: the expression sensors being resolved (a loop).
  std::shared_ptr<const SensorFunction> build(const YAML::Node& node, const std::string& at, const std::string& text,
                                              const std::vector<std::string>& leading, std::vector<int>& nodes,
                                              std::vector<std::string>& chain) {
    std::vector<std::string> known = leading;
    known.push_back("t");
    std::vector<std::string> used;
    try {
      used = expression_names(text);
    } catch (const std::invalid_argument& e) {
      rd_.fail(node, at, e.what());
    }
    // The expression's variables: the names it uses that are the caller's, t, or sensors.
    std::vector<std::string> variables;
    std::vector<int> roles;
    std::vector<SensorFunction::Input> inputs;
    for (const std::string& name : used) {
      const auto k = std::find(known.begin(), known.end(), name);
      if (k != known.end()) {
        const int j = static_cast<int>(k - known.begin());
        roles.push_back(j == static_cast<int>(leading.size()) ? SensorFunction::kTime : SensorFunction::leading(j));
      } else if (rd_.scope().count(name) || name == "pi" || name == "e") {
        continue;  // a parameter or constant
      } else {
        const int s = find_sensor(name);
        if (s < 0) {
          std::string sensors;
          for (const Sensor& sn : model_.sensors()) sensors += (sensors.empty() ? "" : ", ") + sn.name;
          rd_.fail(node, at, "unknown name '" + name + "': no variable (" + join(known) + "), parameter or sensor of that name (sensors: " +
                                 (sensors.empty() ? "none" : sensors) + ")");
        }
        roles.push_back(static_cast<int>(inputs.size()));
        inputs.push_back(input(node, at, s, nodes, chain));
      }
      variables.push_back(name);
    }
    if (variables.size() > ExpressionFunction::kMaxVariables)
      rd_.fail(node, at, "uses " + std::to_string(variables.size()) + " variables and sensors (" + join(variables) + "); an expression may use at most " +
                             std::to_string(ExpressionFunction::kMaxVariables) + " (combine some in an `expression` sensor)");
    std::shared_ptr<const ExpressionFunction> f;
    try {
      f = std::make_shared<ExpressionFunction>(text, rd_.scope(), variables);
    } catch (const std::invalid_argument& e) {
      rd_.fail(node, at, e.what());
    }
    return std::make_shared<SensorFunction>(f, std::move(roles), std::move(inputs));
  }

  /// Resolves pending expression sensor `p` (once): its function on its own node list.
  void resolve(SensorFeedback::PendingSensor& p, std::vector<std::string>& chain) {
    if (p.state == SensorFeedback::PendingSensor::State::done) return;
    p.state = SensorFeedback::PendingSensor::State::resolving;
    chain.push_back(model_.sensors()[static_cast<size_t>(p.index)].name);
    p.function = build(p.node, p.at, p.text, {}, p.nodes, chain);
    if (p.nodes.empty())
      rd_.fail(p.node, p.at, "names no sensor (a function of t and parameters alone is a time function, not a sensor)");
    chain.pop_back();
    p.state = SensorFeedback::PendingSensor::State::done;
  }

 private:
  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }
  int find_sensor(const std::string& name) const {
    const auto& ss = model_.sensors();
    for (size_t i = 0; i < ss.size(); ++i)
      if (ss[i].name == name) return static_cast<int>(i);
    return -1;
  }
  static int slot(std::vector<int>& nodes, int n) {
    const auto it = std::find(nodes.begin(), nodes.end(), n);
    if (it != nodes.end()) return static_cast<int>(it - nodes.begin());
    nodes.push_back(n);
    return static_cast<int>(nodes.size()) - 1;
  }

  SensorFunction::Input input(const YAML::Node& node, const std::string& at, int s, std::vector<int>& nodes,
                              std::vector<std::string>& chain) {
    const Sensor& sn = model_.sensors()[static_cast<size_t>(s)];
    SensorFunction::Input in;
    in.kind = sn.kind;
    auto& pending = feedback(sb_).sensors;
    const auto p = std::find_if(pending.begin(), pending.end(), [&](const auto& x) { return x.index == s && x.integrator < 0; });
    if (p != pending.end()) {
      // An expression sensor (it may be listed later): resolved now, then its function on our nodes.
      if (p->state == SensorFeedback::PendingSensor::State::resolving) {
        std::string loop;
        const auto from = std::find(chain.begin(), chain.end(), sn.name);
        for (auto c = from; c != chain.end(); ++c) loop += *c + " → ";
        rd_.fail(node, at, "reads sensor '" + sn.name + "', which depends on this expression: a loop (" + loop + sn.name +
                               "); break it with an `integral` sensor, whose value is a state");
      }
      resolve(*p, chain);
      std::vector<int> map;
      for (int n : p->nodes) map.push_back(slot(nodes, n));
      in.expression = p->function->rebased(map);
      in.slot = map.front();
      return in;
    }
    switch (sn.kind) {
      case Sensor::Kind::NodeCoordinate:
      case Sensor::Kind::NodeSpeed: in.slot = slot(nodes, sn.node); return in;
      case Sensor::Kind::PointPosition:
      case Sensor::Kind::PointDisplacement:
      case Sensor::Kind::PointVelocity:
        if (!model_.node(sn.node).spatial()) break;
        in.slot = slot(nodes, sn.node);
        if (sn.frame_node >= 0) in.frame_slot = slot(nodes, sn.frame_node);
        in.local = sn.local;
        in.initial = sn.initial;
        in.component = sn.component;
        return in;
      default: break;
    }
    rd_.fail(node, at, "sensor '" + sn.name + "' is " + kind_name(sn.kind) +
                           ", whose derivative a load cannot take: expressions may read joint_angle, joint_speed, joint_displacement, point_position, point_displacement, point_velocity (spatial), integral and expression sensors");
  }

  SceneBuilder& sb_;
  Model& model_;
  Reader& rd_;
};

/// The element index the next pending sensor's element will have (see the header comment).
int next_sensor_element(const Item& it) {
  const SensorFeedback& fb = feedback(it.sb);
  return static_cast<int>(it.model.elements().size() + fb.motors.size() + fb.sensors.size());
}

void read_expression_sensor(const Item& it, Sensor& sn) {
  // Evaluated by its probe element (elements/sensor_feedback.hpp), made once the sensors are read.
  sn.kind = Sensor::Kind::ElementOutput;
  sn.element = next_sensor_element(it);
  sn.component = 0;
  SensorFeedback::PendingSensor p;
  p.index = static_cast<int>(it.model.sensors().size());  // the reader adds the sensor next
  p.node = it.keys.node("value");
  p.at = it.at("value");
  p.text = it.keys.text("value");
  feedback(it.sb).sensors.push_back(p);
}

void read_integral_sensor(const Item& it, Sensor& sn) {
  // The integrator's node w: ẇ is the integral (initial value `initial`), w its own integral.
  Node nd;
  nd.name = it.name + ".integral";
  if (it.model.find_node(nd.name) >= 0) it.rd.fail(it.keys.node("name"), it.at("name"), "a node named '" + nd.name + "' exists already");
  nd.kind = NodeKind::LineParticle2D;
  nd.ndof = nd.nconf = 1;
  nd.line_direction = Eigen::Vector2d::Zero();  // drawn as a fixed point: a controller's state, not a place
  nd.q0 = Eigen::VectorXd::Zero(1);
  nd.v0 = Eigen::VectorXd::Constant(1, it.keys.number("initial", 0.0));
  sn.node = it.model.add_node(nd);
  sn.kind = Sensor::Kind::NodeSpeed;
  SensorFeedback::PendingSensor p;
  p.node = it.keys.node("of");
  p.at = it.at("of");
  p.text = it.keys.text("of");
  p.integrator = sn.node;
  p.index = static_cast<int>(it.model.sensors().size());
  feedback(it.sb).sensors.push_back(p);
}

}  // namespace

bool read_feedback_motor(const Item& it, const JointCoordinateNode& psi, const char* key) {
  const std::string text = it.keys.text(key);
  std::vector<std::string> names;
  try {
    names = expression_names(text);
  } catch (const std::invalid_argument& e) {
    it.rd.fail(it.keys.node(key), it.at(key), e.what());
  }
  const std::vector<std::string> leading{psi.variable(), "speed"};
  const bool reads_sensors = std::any_of(names.begin(), names.end(), [&](const std::string& n) {
    return n != leading[0] && n != leading[1] && n != "t" && !it.rd.scope().count(n) && n != "pi" && n != "e";
  });
  if (!reads_sensors) return false;
  feedback(it.sb).motors.push_back({it.name, psi.node, it.keys.node(key), it.at(key), text, leading});
  return true;
}

int pending_motor_element(const Item& it, const std::string& name) {
  const auto& motors = feedback(it.sb).motors;
  for (size_t k = 0; k < motors.size(); ++k)
    if (motors[k].name == name) return static_cast<int>(it.model.elements().size() + k);
  return -1;
}

void begin_sensor_feedback(const SceneBuilder& sb) { registry().erase(&sb); }

void resolve_sensor_feedback(SceneBuilder& sb) {
  const auto found = registry().find(&sb);
  if (found == registry().end()) return;
  SensorFeedback& fb = found->second;
  Model& model = sb.model_;
  Builder b(sb);
  const auto add = [&](std::unique_ptr<Element> e) {
    model.add_element(std::move(e));
  };
  for (const auto& m : fb.motors) {
    std::vector<int> nodes{m.psi};
    std::vector<std::string> chain;
    auto law = b.build(m.node, m.at, m.text, m.leading, nodes, chain);
    add(std::make_unique<SensorFeedbackForce>(m.name, nodes, slot_offsets(model, nodes), law, SensorFeedbackForce::Role::motor));
  }
  for (auto& p : fb.sensors) {
    std::vector<std::string> chain;
    const std::string name = model.sensors()[static_cast<size_t>(p.index)].name;
    if (p.integrator < 0) {
      b.resolve(p, chain);
      const Sensor& sn = model.sensors()[static_cast<size_t>(p.index)];
      if (sn.element != static_cast<int>(model.elements().size()))
        throw std::logic_error("sensor '" + name + "': its probe element is not where the sensor was told it would be");
      add(std::make_unique<SensorFeedbackForce>(name + ".expression", p.nodes, slot_offsets(model, p.nodes), p.function,
                                                SensorFeedbackForce::Role::probe));
      continue;
    }
    // An integral: the element ẅ − e(t, sensors) on [w, the nodes e reads].
    std::vector<int> nodes{p.integrator};
    auto law = b.build(p.node, p.at, p.text, {}, nodes, chain);
    add(std::make_unique<SensorFeedbackForce>(name + ".integral", nodes, slot_offsets(model, nodes), law,
                                              SensorFeedbackForce::Role::integrator));
  }
  registry().erase(found);
}

void register_sensor_feedback_3d(SceneTypes& t) {
  t.sensors.add("expression", type_schema("sensors.3d.expression",
      "`expression`: a function of other sensors and t, e.g. a controller's error (units of the expression)", {
      {"value", KeyType::Text, "of the expression", kRequired,
       "an expression of `t` (s), `parameters` and sensors by name (any sensor of the list, before or after this one; no loops)"}}),
      read_expression_sensor);
  t.sensors.add("integral", type_schema("sensors.3d.integral",
      "`integral`: ∫₀ᵗ e dt + initial of an expression e of sensors, a state of the model (a PID controller's I term)", {
      {"of", KeyType::Text, "of e", kRequired, "the integrand e: an expression of `t`, `parameters` and sensors by name"},
      {"initial", KeyType::Number, "of e × s", "0", "the integral at t = 0"}}),
      read_integral_sensor);
}

}  // namespace alphaflex::scene_detail
