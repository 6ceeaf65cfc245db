// Model building: bodies, force elements (with Python callables), joints, rolling, contacts,
// and the State.

#include <memory>
#include <string>

#include "bindings.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/model/constraints.h"
#include "chasles/model/contact.h"
#include "chasles/model/contact_set.h"
#include "chasles/model/data.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"
#include "chasles/model/string_constraint.h"

namespace chasles::python {

namespace {

/// A Python callable fn(t, state) -> 3-vector as a VectorFunction (GilSafe). The time is read
/// from the state (state.t).
VectorFunction PythonVectorFunction(py::function fn) {
  return GilSafe<Vec3, const Model&, const State&>(
      std::move(fn), [](const py::function& f, const Model& /*model*/, const State& state) {
        return CallbackResult<Vec3>(f, f(state.t, state), "3 numbers [x, y, z]");
      });
}

/// A Python callable fn(t, state) -> float as a ScalarFunction (a tension, a torque).
ScalarFunction PythonScalarFunction(py::function fn) {
  return GilSafe<double, const Model&, const State&>(
      std::move(fn), [](const py::function& f, const Model& /*model*/, const State& state) {
        return CallbackResult<double>(f, f(state.t, state), "a number");
      });
}

ScalarFunction ConstantScalar(double value) {
  return [value](const Model&, const State&) { return value; };
}

/// A drum's or pulley's sense: +1 counterclockwise, -1 clockwise (as the scene's words).
int SenseFrom(const std::string& sense) {
  if (sense == "counterclockwise") return 1;
  if (sense == "clockwise") return -1;
  throw InputError("sense must be 'counterclockwise' or 'clockwise', got '" + sense + "'");
}

/// A Python callable fn(t) -> float as one function of a TimeFunction.
std::function<double(double)> PythonTimeFunction(py::function fn) {
  return GilSafe<double, double>(std::move(fn), [](const py::function& f, double t) {
    return CallbackResult<double>(f, f(t), "a number");
  });
}

VectorFrame FrameFrom(const std::string& frame) {
  if (frame == "world") return VectorFrame::kWorld;
  if (frame == "body") return VectorFrame::kBody;
  throw InputError("frame must be 'world' or 'body', got '" + frame + "'");
}

/// A set of bodies given from Python: "all", a name or a pattern (one str), or a list of names
/// and patterns; TypeError for anything else.
BodySet BodySetFrom(const py::handle& value, const char* argument) {
  if (py::isinstance<py::str>(value)) return BodySetOfText(value.cast<std::string>());
  if (py::isinstance<py::sequence>(value)) {
    BodySet set;
    for (const py::handle item : value.cast<py::sequence>()) {
      if (!py::isinstance<py::str>(item)) {
        throw py::type_error(std::string(argument) +
                             ": every item must be a str (a body's "
                             "name or a pattern)");
      }
      set.items.push_back(item.cast<std::string>());
    }
    return set;
  }
  throw py::type_error(std::string(argument) +
                       " must be 'all', a body's name, a pattern such as 'ball*', or a list of "
                       "names and patterns");
}

/// Model.add_contact_set: the sets from the keywords, then AddContactSet; a set's error names
/// the argument and item it is about.
std::vector<int> AddContactSetFromPython(Model& model, const ContactSpec& spec,
                                         const py::object& bodies, const py::object& with_bodies,
                                         const py::object& between) {
  if (bodies.is_none() == between.is_none()) {
    throw InputError(
        "add_contact_set: give either bodies= (with a plane, or with with_bodies=) "
        "or between= (every pair within one set)");
  }
  if (!between.is_none() && !with_bodies.is_none()) {
    throw InputError("add_contact_set: with_bodies= goes with bodies=, not with between=");
  }
  ContactBodySets sets;
  sets.between = !between.is_none();
  sets.bodies = BodySetFrom(sets.between ? between : bodies, sets.between ? "between" : "bodies");
  sets.has_with = !with_bodies.is_none();
  if (sets.has_with) sets.with = BodySetFrom(with_bodies, "with_bodies");
  try {
    return AddContactSet(model, spec, sets);
  } catch (const BodySetError& e) {
    const bool with = e.role() == BodySetRole::kWith;
    const char* argument = with ? "with_bodies" : sets.between ? "between" : "bodies";
    const bool listed = !py::isinstance<py::str>(with           ? with_bodies
                                                 : sets.between ? between
                                                                : bodies);
    const std::string item = listed && e.item() >= 0 ? "[" + std::to_string(e.item()) + "]" : "";
    throw InputError(std::string(argument) + item + ": " + e.what());
  }
}

/// A body of `model` (IndexError otherwise) in a state made for it (InputError otherwise):
/// the state functions index both.
void CheckBodyOfState(const Model& model, const State& state, int body) {
  CheckIndex(body, model.num_bodies(), "body", "num_bodies");
  if (state.bodies.size() != static_cast<size_t>(model.num_bodies())) {
    throw InputError("the state has " + std::to_string(state.bodies.size()) +
                     " bodies and the model " + std::to_string(model.num_bodies()) +
                     ": make the state with make_rest_state(model) after the last body is added");
  }
}

/// AttachmentFrameAtWorldPose for a body of the model and state (or WORLD), at a finite pose.
AttachmentFrame CheckedAttachmentFrameAtWorldPose(const Model& model, const State& state,
                                                  BodyIndex b, const Vec3& p, const Mat3& R) {
  if (b != kWorld) CheckBodyOfState(model, state, b);
  return AttachmentFrameAtWorldPose(model, state, b, RequireFinite(p, "position"),
                                    RequireFinite(R, "rotation"));
}

/// The forces given by a tension or a torque: cables, strings pulled by hand, joint torques.
void BindTensionForces(py::module_& m) {
  py::class_<CableForce, ForceElement, std::shared_ptr<CableForce>>(
      m, "CableForce",
      "A cable from a point of a body (from Bo in B [m]) to a fixed world point (the winch), "
      "pulling with tension >= 0 [N]: a number or a callable fn(t, state).")
      .def(py::init([](std::string name, BodyIndex body, const Vec3& point, const Vec3& winch,
                       double tension) {
             return std::make_shared<CableForce>(std::move(name), body, point, winch,
                                                 ConstantScalar(tension));
           }),
           py::arg("name"), py::arg("body"), py::arg("point"), py::arg("winch"), py::arg("tension"))
      .def(py::init([](std::string name, BodyIndex body, const Vec3& point, const Vec3& winch,
                       py::function tension) {
             return std::make_shared<CableForce>(std::move(name), body, point, winch,
                                                 PythonScalarFunction(std::move(tension)));
           }),
           py::arg("name"), py::arg("body"), py::arg("point"), py::arg("winch"),
           py::arg("tension"));
  py::class_<StringPull, ForceElement, std::shared_ptr<StringPull>>(
      m, "StringPull",
      "A string wound on a drum of a body (centre from Bo in B [m], axis in B, radius [m]) "
      "pulled by hand with tension >= 0 [N] (a number or fn(t, state)) along a fixed world "
      "direction; sense 'counterclockwise' or 'clockwise': the way the string, followed from "
      "the drum to the hand, leaves the drum about the axis. It acts at the tangent point "
      "c - s r a x d.")
      .def(py::init([](std::string name, BodyIndex body, const Vec3& centre, const Vec3& axis,
                       double radius, const std::string& sense, const Vec3& direction,
                       double tension) {
             return std::make_shared<StringPull>(std::move(name), body, centre, axis, radius,
                                                 SenseFrom(sense), direction,
                                                 ConstantScalar(tension));
           }),
           py::arg("name"), py::arg("body"), py::arg("centre"), py::arg("axis"), py::arg("radius"),
           py::arg("sense"), py::arg("direction"), py::arg("tension"))
      .def(py::init([](std::string name, BodyIndex body, const Vec3& centre, const Vec3& axis,
                       double radius, const std::string& sense, const Vec3& direction,
                       py::function tension) {
             return std::make_shared<StringPull>(std::move(name), body, centre, axis, radius,
                                                 SenseFrom(sense), direction,
                                                 PythonScalarFunction(std::move(tension)));
           }),
           py::arg("name"), py::arg("body"), py::arg("centre"), py::arg("axis"), py::arg("radius"),
           py::arg("sense"), py::arg("direction"), py::arg("tension"))
      .def(
          "tangent_point",
          [](const StringPull& f, const Model& model, const State& state) {
            Data data = MakeData(model);
            CalcKinematics(model, state, data);
            return f.CalcTangentPoint(model, state, data);
          },
          py::arg("model"), py::arg("state"), "Where the string leaves the drum, in W [m].");
  py::class_<JointTorque, ForceElement, std::shared_ptr<JointTorque>>(
      m, "JointTorque",
      "A torque [N*m] (a number or fn(t, state)) about an axis fixed in the parent (in W for "
      "WORLD): +torque on the child, -torque on the parent.")
      .def(py::init([](std::string name, BodyIndex parent, BodyIndex child, const Vec3& axis,
                       double torque) {
             return std::make_shared<JointTorque>(std::move(name), parent, child, axis,
                                                  ConstantScalar(torque));
           }),
           py::arg("name"), py::arg("parent"), py::arg("child"), py::arg("axis"), py::arg("torque"))
      .def(py::init([](std::string name, BodyIndex parent, BodyIndex child, const Vec3& axis,
                       py::function torque) {
             return std::make_shared<JointTorque>(std::move(name), parent, child, axis,
                                                  PythonScalarFunction(std::move(torque)));
           }),
           py::arg("name"), py::arg("parent"), py::arg("child"), py::arg("axis"),
           py::arg("torque"));
}

void BindForces(py::module_& m) {
  py::class_<ForceElement, std::shared_ptr<ForceElement>>(
      m, "ForceElement", "Something that pushes on bodies; add it with Model.add_force_element.")
      .def_property_readonly("name", &ForceElement::name)
      .def_property_readonly("has_potential", &ForceElement::has_potential)
      .def_property_readonly("is_dissipative", &ForceElement::is_dissipative);
  py::class_<UniformGravity, ForceElement, std::shared_ptr<UniformGravity>>(
      m, "UniformGravity", "Uniform gravity g [m/s^2] on every body, at its centre of mass.")
      .def(py::init<std::string, const Vec3&>(), py::arg("name"), py::arg("g"))
      .def_property_readonly("g", &UniformGravity::g_W);
  py::class_<CentralGravity, ForceElement, std::shared_ptr<CentralGravity>>(
      m, "CentralGravity", "Inverse-square gravity towards a fixed point: mu = G M [m^3/s^2].")
      .def(py::init<std::string, double, const Vec3&>(), py::arg("name"), py::arg("mu"),
           py::arg("centre"));
  py::class_<AppliedForce, ForceElement, std::shared_ptr<AppliedForce>>(
      m, "AppliedForce",
      "A force at a point of a body (point from its frame origin, in B [m]). The force is a "
      "constant 3-vector [N] or a callable fn(t, state) returning one; frame 'world' or "
      "'body'.")
      .def(py::init([](std::string name, BodyIndex body, const Vec3& point, const Vec3& force,
                       const std::string& frame, const std::string& point_frame) {
             return std::make_shared<AppliedForce>(
                 std::move(name), body, point, FrameFrom(point_frame),
                 [force](const Model&, const State&) { return force; }, FrameFrom(frame));
           }),
           py::arg("name"), py::arg("body"), py::arg("point"), py::arg("force"),
           py::arg("frame") = "world", py::arg("point_frame") = "body",
           "point_frame 'body': the point from Bo in B, fixed in the body; 'world': a world "
           "point, the force acting on the material point there at each instant")
      .def(py::init([](std::string name, BodyIndex body, const Vec3& point, py::function force,
                       const std::string& frame, const std::string& point_frame) {
             return std::make_shared<AppliedForce>(
                 std::move(name), body, point, FrameFrom(point_frame),
                 PythonVectorFunction(std::move(force)), FrameFrom(frame));
           }),
           py::arg("name"), py::arg("body"), py::arg("point"), py::arg("force"),
           py::arg("frame") = "world", py::arg("point_frame") = "body");
  py::class_<AppliedMoment, ForceElement, std::shared_ptr<AppliedMoment>>(
      m, "AppliedMoment",
      "A pure moment [N*m] on a body: a constant 3-vector or a callable fn(t, state); frame "
      "'world' or 'body'.")
      .def(py::init(
               [](std::string name, BodyIndex body, const Vec3& moment, const std::string& frame) {
                 return AppliedMoment::Constant(std::move(name), body, moment, FrameFrom(frame));
               }),
           py::arg("name"), py::arg("body"), py::arg("moment"), py::arg("frame") = "world")
      .def(py::init([](std::string name, BodyIndex body, py::function moment,
                       const std::string& frame) {
             return std::make_shared<AppliedMoment>(
                 std::move(name), body, PythonVectorFunction(std::move(moment)), FrameFrom(frame));
           }),
           py::arg("name"), py::arg("body"), py::arg("moment"), py::arg("frame") = "world");
  py::class_<SpringDamper, ForceElement, std::shared_ptr<SpringDamper>>(
      m, "SpringDamper",
      "Linear spring-damper between point P of body A and point Q of body B (or a world "
      "point when body_b is WORLD): tension k (L - L0) + c dL/dt.")
      .def(py::init<std::string, BodyIndex, const Vec3&, BodyIndex, const Vec3&, double, double,
                    double>(),
           py::arg("name"), py::arg("body_a"), py::arg("point_a"), py::arg("body_b"),
           py::arg("point_b"), py::arg("rest_length"), py::arg("stiffness"),
           py::arg("damping") = 0.0);
  py::class_<LinearDrag, ForceElement, std::shared_ptr<LinearDrag>>(
      m, "LinearDrag", "Viscous drag: F = -c v at the centre of mass, M = -c_w w.")
      .def(py::init<std::string, BodyIndex, double, double>(), py::arg("name"), py::arg("body"),
           py::arg("linear"), py::arg("angular") = 0.0);
  BindTensionForces(m);
}

/// Strings: their ends, pulleys and the constraint.
void BindStrings(py::module_& m) {
  py::class_<StringEnd>(m, "StringEnd",
                        "An end of a string: a point of a body (radius 0) or a drum of it "
                        "(point = the drum's centre), from Bo in B (in W for WORLD) [m].")
      .def(py::init([](BodyIndex body, const Vec3& point, double radius, const std::string& sense) {
             return StringEnd{body, point, radius, SenseFrom(sense)};
           }),
           py::arg("body"), py::arg("point"), py::arg("radius") = 0.0,
           py::arg("sense") = "counterclockwise")
      .def_readwrite("body", &StringEnd::body)
      .def_readwrite("point", &StringEnd::p_BoP_B)
      .def_readwrite("radius", &StringEnd::radius)
      .def_readwrite("sense", &StringEnd::sense, "+1 counterclockwise, -1 clockwise");
  py::class_<StringPulley>(m, "StringPulley",
                           "A massless frictionless pulley: fixed (body WORLD, centre in W) or "
                           "carried by a body (centre from Bo in B) [m].")
      .def(
          py::init([](const Vec3& centre, double radius, const std::string& sense, BodyIndex body) {
            return StringPulley{centre, radius, SenseFrom(sense), body};
          }),
          py::arg("centre"), py::arg("radius"), py::arg("sense"), py::arg("body") = kWorld)
      .def_readwrite("centre", &StringPulley::p_BoO_B)
      .def_readwrite("radius", &StringPulley::radius)
      .def_readwrite("sense", &StringPulley::sense, "+1 counterclockwise, -1 clockwise")
      .def_readwrite("body", &StringPulley::body);
  py::class_<StringConstraint, Constraint, std::shared_ptr<StringConstraint>>(
      m, "StringConstraint",
      "An inextensible string held taut from end a (the parent) over pulleys to end b (the "
      "child), in the plane normal to `normal`, keeping the free length `length` [m] (use "
      "free_length at the initial state). Its multiplier is the tension [N]. Senses: the way "
      "the string, followed from a to b, goes round each circle about the normal.")
      .def(py::init<std::string, const StringEnd&, std::vector<StringPulley>, const StringEnd&,
                    const Vec3&, double>(),
           py::arg("name"), py::arg("a"), py::arg("pulleys"), py::arg("b"), py::arg("normal"),
           py::arg("length"))
      .def_static(
          "free_length",
          [](const Model& model, const State& state, const StringEnd& a,
             const std::vector<StringPulley>& pulleys, const StringEnd& b, const Vec3& normal) {
            const StringConstraint probe("probe", a, pulleys, b, normal, 1.0);
            Data data = MakeData(model);
            CalcKinematics(model, state, data);
            return probe.CalcPath(model, state, data).length;
          },
          py::arg("model"), py::arg("state"), py::arg("a"), py::arg("pulleys"), py::arg("b"),
          py::arg("normal"),
          "The free length L (segments plus arcs on the pulleys) of that path at `state` [m].")
      .def_property_readonly("length", &StringConstraint::length);
}

/// Gears in mesh and drivers (prescribed motions).
void BindGearsAndDrivers(py::module_& m) {
  py::enum_<GearKind>(m, "GearKind", "How two pitch circles mesh.")
      .value("EXTERNAL", GearKind::kExternal)
      .value("INTERNAL", GearKind::kInternal)
      .value("FACE", GearKind::kFace);
  py::class_<PitchCircle>(m, "PitchCircle", "A gear's pitch circle on its body.")
      .def(py::init([](const Vec3& centre, const Vec3& axis, double radius) {
             PitchCircle c;
             c.p_BoO_B = centre;
             c.axis_B = axis;
             c.radius = radius;
             return c;
           }),
           py::arg("centre"), py::arg("axis"), py::arg("radius"),
           "centre from Bo in B (in W on the world) [m], unit axis in B, pitch radius [m]")
      .def_readwrite("centre", &PitchCircle::p_BoO_B, "Centre from Bo, in B [m]")
      .def_readwrite("axis", &PitchCircle::axis_B, "Unit axis, in B")
      .def_readwrite("radius", &PitchCircle::radius, "Pitch radius [m]");
  py::class_<GearMesh, Constraint, std::shared_ptr<GearMesh>>(
      m, "GearMesh",
      "Two gears in mesh: their pitch circles roll on each other without slipping. "
      "keep_contact adds the row that keeps the pitch circles touching (leave it out when "
      "bearings fix the centre distance). Multipliers: the mesh force [N] (and the separating "
      "force).")
      .def(py::init<std::string, GearKind, BodyIndex, const PitchCircle&, BodyIndex,
                    const PitchCircle&, bool>(),
           py::arg("name"), py::arg("kind"), py::arg("parent"), py::arg("parent_circle"),
           py::arg("child"), py::arg("child_circle"), py::arg("keep_contact") = false);
  py::class_<TimeFunction>(m, "TimeFunction",
                           "A prescribed f(t) with its rate and acceleration (for drivers).")
      .def(py::init([](py::function value, py::function rate, py::function acceleration) {
             return TimeFunction{PythonTimeFunction(std::move(value)),
                                 PythonTimeFunction(std::move(rate)),
                                 PythonTimeFunction(std::move(acceleration))};
           }),
           py::arg("value"), py::arg("rate"), py::arg("acceleration"),
           "Three callables of t: f(t) [m or rad], its rate and its acceleration.")
      .def_static("quadratic", &TimeFunction::Quadratic, py::arg("f0"), py::arg("f1"),
                  py::arg("f2"), "f = f0 + f1 t + f2 t^2 / 2");
  py::enum_<DriverKind>(m, "DriverKind", "What a PrescribedMotion drives.")
      .value("TRANSLATION", DriverKind::kTranslation)
      .value("ROTATION", DriverKind::kRotation);
  py::class_<PrescribedMotion, Constraint, std::shared_ptr<PrescribedMotion>>(
      m, "PrescribedMotion",
      "A driver: the child's J origin along the parent's z axis (TRANSLATION), or the angle "
      "from a_x to b_x about a_z (ROTATION, with a revolute joint on z), follows f(t). Its "
      "multiplier is the force [N] or moment [N m] the driver supplies.")
      .def(py::init<std::string, DriverKind, BodyIndex, const AttachmentFrame&, BodyIndex,
                    const AttachmentFrame&, TimeFunction>(),
           py::arg("name"), py::arg("kind"), py::arg("parent"), py::arg("parent_frame"),
           py::arg("child"), py::arg("child_frame"), py::arg("f"));
}

void BindConstraints(py::module_& m) {
  py::class_<AttachmentFrame>(m, "AttachmentFrame",
                              "A frame on a body: origin from Bo in B [m] and axes R_BJ "
                              "(columns; z is the joint axis); world pose for WORLD.")
      .def(py::init([](const Vec3& p, const Mat3& R) {
             return AttachmentFrame{p, R};
           }),
           py::arg("origin"), py::arg("rotation") = Mat3::Identity())
      .def_readwrite("origin", &AttachmentFrame::p_BoJ_B)
      .def_readwrite("rotation", &AttachmentFrame::R_BJ);
  py::enum_<JointKind>(m, "JointKind", "Kinds of ideal joints (see constraints.h).")
      .value("WELD", JointKind::kWeld)
      .value("REVOLUTE", JointKind::kRevolute)
      .value("PRISMATIC", JointKind::kPrismatic)
      .value("SPHERICAL", JointKind::kSpherical)
      .value("CYLINDRICAL", JointKind::kCylindrical)
      .value("PLANAR", JointKind::kPlanar)
      .value("POINT_ON_PLANE", JointKind::kPointOnPlane)
      .value("POINT_ON_LINE", JointKind::kPointOnLine)
      .value("REVOLUTE_IN_PLANE", JointKind::kRevoluteInPlane)
      .value("PRISMATIC_IN_PLANE", JointKind::kPrismaticInPlane)
      .value("WELD_IN_PLANE", JointKind::kWeldInPlane)
      .value("POINT_ON_LINE_IN_PLANE", JointKind::kPointOnLineInPlane);
  py::enum_<RollingShape>(m, "RollingShape", "Round shapes that roll on a plane.")
      .value("SPHERE", RollingShape::kSphere)
      .value("CYLINDER", RollingShape::kCylinder)
      .value("DISK", RollingShape::kDisk)
      .value("WHEEL_IN_PLANE", RollingShape::kWheelInPlane);
  py::class_<Constraint, std::shared_ptr<Constraint>>(
      m, "Constraint", "A joint, rolling contact or driver; add it with Model.add_constraint.")
      .def_property_readonly("name", &Constraint::name)
      .def_property_readonly("kind", &Constraint::kind)
      .def_property_readonly("parent", &Constraint::parent)
      .def_property_readonly("child", &Constraint::child)
      .def_property_readonly("num_rows", &Constraint::num_rows);
  py::class_<Joint, Constraint, std::shared_ptr<Joint>>(
      m, "Joint", "An ideal joint between a parent (or WORLD) and a child, frames on both.")
      .def(py::init<std::string, JointKind, BodyIndex, const AttachmentFrame&, BodyIndex,
                    const AttachmentFrame&>(),
           py::arg("name"), py::arg("kind"), py::arg("parent"), py::arg("parent_frame"),
           py::arg("child"), py::arg("child_frame"));
  py::class_<RollingContact, Constraint, std::shared_ptr<RollingContact>>(
      m, "RollingContact",
      "Rolling without slipping of a round body on a fixed world plane (through plane_point "
      "with upward normal plane_normal). centre from Bo in B [m], axis in B, radius [m].")
      .def(py::init<std::string, RollingShape, BodyIndex, const Vec3&, const Vec3&, double,
                    const Vec3&, const Vec3&>(),
           py::arg("name"), py::arg("shape"), py::arg("body"), py::arg("centre"), py::arg("axis"),
           py::arg("radius"), py::arg("plane_point"), py::arg("plane_normal"));
  BindStrings(m);
  BindGearsAndDrivers(m);
  m.def("attachment_frame_at_world_pose", &CheckedAttachmentFrameAtWorldPose, py::arg("model"),
        py::arg("state"), py::arg("body"), py::arg("position"),
        py::arg("rotation") = Mat3::Identity(),
        "The frame on `body` (or WORLD) that coincides with the world pose at `state`.");
  m.def("frame_with_z_axis", &FrameWithZAxis, py::arg("axis"),
        "A rotation whose z column is the unit vector along `axis`.");
}

void BindContacts(py::module_& m) {
  py::enum_<ContactShape>(m, "ContactShape", "Shapes of unilateral contacts.")
      .value("SPHERE", ContactShape::kSphere)
      .value("DISK_RIM", ContactShape::kDiskRim)
      .value("DISK_FACE", ContactShape::kDiskFace)
      .value("CYLINDER", ContactShape::kCylinder)
      .value("BOX", ContactShape::kBox)
      .value("POINT_SET", ContactShape::kPointSet)
      .value("CAPSULE", ContactShape::kCapsule)
      .value("SPHERE_SPHERE", ContactShape::kSphereSphere);
  py::enum_<ContactMode>(m, "ContactMode", "Mode of a contact point.")
      .value("SEPARATED", ContactMode::kSeparated)
      .value("SLIDING", ContactMode::kSliding)
      .value("STICKING", ContactMode::kSticking);
  py::enum_<RestitutionLaw>(m, "RestitutionLaw", "How restitution ends an impact.")
      .value("ENERGETIC", RestitutionLaw::kEnergetic)
      .value("NEWTON", RestitutionLaw::kNewton)
      .value("POISSON", RestitutionLaw::kPoisson);
  py::class_<ContactSpec>(m, "ContactSpec",
                          "A unilateral contact with Coulomb friction against a world plane "
                          "(or another sphere); set the fields the shape reads, then "
                          "Model.add_contact. Lengths from Bo in B [m].")
      .def(py::init([](std::string name, ContactShape shape, BodyIndex body, py::kwargs kw) {
             ContactSpec s;
             s.name = std::move(name);
             s.shape = shape;
             s.body = body;
             py::object self = py::cast(s);
             for (auto item : kw) self.attr(item.first) = item.second;
             return self.cast<ContactSpec>();
           }),
           py::arg("name"), py::arg("shape"), py::arg("body"),
           "ContactSpec(name, shape, body, **fields): any field below as a keyword.")
      .def_readwrite("name", &ContactSpec::name)
      .def_readwrite("shape", &ContactSpec::shape)
      .def_readwrite("body", &ContactSpec::body)
      .def_readwrite("centre", &ContactSpec::p_BoC_B, "Centre of the shape from Bo in B [m]")
      .def_readwrite("axis", &ContactSpec::axis_B, "Axis of a disk, cylinder, capsule (in B)")
      .def_readwrite("radius", &ContactSpec::radius, "[m]")
      .def_readwrite("length", &ContactSpec::length, "Cylinder or capsule segment length [m]")
      .def_readwrite("half_extents", &ContactSpec::half_extents, "Box half extents [m]")
      .def_readwrite("box_axes", &ContactSpec::R_BF, "Box axes in B (columns)")
      .def_readwrite("points", &ContactSpec::points_B, "Point-set points from Bo in B [m]")
      .def_readwrite("face_points", &ContactSpec::face_points)
      .def_readwrite("other_body", &ContactSpec::other_body)
      .def_readwrite("other_centre", &ContactSpec::p_OoC_O)
      .def_readwrite("other_radius", &ContactSpec::other_radius)
      .def_readwrite("plane_point", &ContactSpec::plane_point_W, "A point of the plane [m]")
      .def_readwrite("plane_normal", &ContactSpec::plane_normal_W, "Plane normal towards the body")
      .def_readwrite("mu_s", &ContactSpec::mu_s)
      .def_readwrite("mu_k", &ContactSpec::mu_k)
      .def_readwrite("mu_r", &ContactSpec::mu_r)
      .def_readwrite("restitution", &ContactSpec::restitution)
      .def_readwrite("restitution_law", &ContactSpec::restitution_law);
}

void BindState(py::module_& m) {
  py::class_<BodyState>(m, "BodyState", "Motion of one body (SI, world frame W).")
      .def_readwrite("position", &BodyState::p_WBcm, "Centre of mass in W [m]")
      .def_property(
          "quaternion", [](const BodyState& b) { return QuatArray(b.q_WB); },
          [](BodyState& b, const Eigen::Vector4d& q) { b.q_WB = QuatFrom(q); },
          "Orientation [w, x, y, z]")
      .def_property_readonly(
          "rotation", [](const BodyState& b) { return Mat3(b.q_WB.toRotationMatrix()); },
          "R_WB (3x3)")
      .def_readwrite("velocity", &BodyState::v_WBcm_W, "Velocity of the centre of mass [m/s]")
      .def_readwrite("angular_velocity_body", &BodyState::w_WB_B, "Angular velocity in B [rad/s]")
      .def_property_readonly(
          "angular_velocity", [](const BodyState& b) { return Vec3(b.q_WB * b.w_WB_B); },
          "Angular velocity in W [rad/s]");
  py::class_<State>(m, "State", "Time and the motion of every body (make_rest_state makes one).")
      .def_readwrite("t", &State::t, "Time [s]")
      .def_property_readonly(
          "bodies",
          [](py::object self) {
            State& s = self.cast<State&>();
            py::list out;
            for (BodyState& b : s.bodies) {
              out.append(py::cast(&b, py::return_value_policy::reference_internal, self));
            }
            return out;
          },
          "The bodies' states (views into this State; Model order)")
      .def(
          "copy", [](const State& s) { return State(s); }, "A copy.");
  m.def("make_rest_state", &MakeRestState, py::arg("model"),
        "A state at t = 0 with every body at rest at the origin, identity orientation.");
  m.def(
      "set_body_pose",
      [](const Model& model, int b, const Vec3& p, const Eigen::Vector4d& q, State& state) {
        CheckBodyOfState(model, state, b);
        RequireFinite(p, "origin");
        if (!(RequireFinite(q, "quaternion").norm() > 0.0)) {
          throw InputError("quaternion must not be zero");
        }
        SetBodyPose(model, b, p, QuatFrom(q), state);
      },
      py::arg("model"), py::arg("body"), py::arg("origin"), py::arg("quaternion"), py::arg("state"),
      "Places body's frame origin at `origin` with orientation [w, x, y, z].");
  m.def(
      "set_body_velocity",
      [](const Model& model, int b, const Vec3& v, const Vec3& w, State& state) {
        CheckBodyOfState(model, state, b);
        SetBodyVelocity(model, b, RequireFinite(v, "origin_velocity"),
                        RequireFinite(w, "angular_velocity"), state);
      },
      py::arg("model"), py::arg("body"), py::arg("origin_velocity"), py::arg("angular_velocity"),
      py::arg("state"),
      "Sets the velocity of body's frame origin and its angular velocity (both in W).");
  m.def(
      "body_origin_position",
      [](const Model& model, const State& state, int b) {
        CheckBodyOfState(model, state, b);
        return CalcBodyOriginPosition(model, state, b);
      },
      py::arg("model"), py::arg("state"), py::arg("body"),
      "Position of body's frame origin in W [m].");
  m.def("validate_state", &ValidateState, py::arg("model"), py::arg("state"),
        "Raises InputError when the state does not fit the model or is not finite.");
}

void BindModelClass(py::module_& m) {
  m.attr("WORLD") = kWorld;
  py::class_<Body>(m, "Body", "A free rigid body of a Model.")
      .def_property_readonly("name", &Body::name)
      .def_property_readonly("mass", &Body::mass, "[kg]")
      .def_property_readonly("mass_properties", &Body::mass_properties)
      .def_property_readonly("center_of_mass", &Body::p_BoBcm_B, "From Bo in B [m]")
      .def_property_readonly("inertia", &Body::I_BBcm_B, "About the centre of mass in B");
  py::class_<Model, std::shared_ptr<Model>>(
      m, "Model", "Bodies, force elements, constraints and contacts of a system.")
      .def(py::init<>())
      .def("add_body", &Model::AddBody, py::arg("name"), py::arg("mass_properties"),
           "Adds a free body; returns its index.")
      .def(
          "add_force_element",
          [](Model& model, std::shared_ptr<ForceElement> e) { return model.AddForceElement(e); },
          py::arg("element"), "Adds a force element; returns its index.")
      .def(
          "add_constraint",
          [](Model& model, std::shared_ptr<Constraint> c) { return model.AddConstraint(c); },
          py::arg("constraint"), "Adds a joint, rolling contact or driver; returns its index.")
      .def("add_contact", &Model::AddContact, py::arg("spec"),
           "Adds a unilateral contact; returns its index.")
      .def("add_contact_set", &AddContactSetFromPython, py::arg("spec"),
           py::arg("bodies") = py::none(), py::arg("with_bodies") = py::none(),
           py::arg("between") = py::none(),
           "Adds the contacts a set of bodies stands for, each a copy of `spec` (its name the "
           "base of theirs): bodies= one per body (against spec's plane), with with_bodies= "
           "one per pair across the two sets, between= one per pair within the set (shape "
           "SPHERE_SPHERE for pairs). A set is 'all', a body's name, a pattern ('*' any run "
           "of characters, '?' one character) or a list of names and patterns; the contacts "
           "come in body order, named <name>_<body> or <name>_<a>_<b> (docs/scene-format.md, "
           "'Sets of bodies'). Returns their indices; InputError, with the model unchanged, "
           "for a set that names no body, more than 20000 contacts, or a contact that repeats "
           "one of the model's.")
      .def_property_readonly("num_bodies", &Model::num_bodies)
      .def_property_readonly("num_force_elements", &Model::num_force_elements)
      .def_property_readonly("num_constraints", &Model::num_constraints)
      .def_property_readonly("num_contacts", &Model::num_contacts)
      .def_property_readonly("num_contact_points", &Model::num_contact_points)
      .def(
          "body",
          [](const Model& model, int index) -> const Body& {
            CheckIndex(index, model.num_bodies(), "body", "num_bodies");
            return model.body(index);
          },
          py::arg("index"), py::return_value_policy::reference_internal,
          "The body at `index` (0 to num_bodies - 1); IndexError otherwise.")
      .def("find_body", &Model::FindBody, py::arg("name"))
      .def(
          "contact_point_name",
          [](const Model& model, int point) {
            CheckIndex(point, model.num_contact_points(), "point", "num_contact_points");
            return model.contact_point_name(point);
          },
          py::arg("point"), "The name of contact point `point`; IndexError when out of range.");
}

}  // namespace

void CheckIndex(int index, int count, const char* argument, const char* count_name) {
  if (index < 0 || index >= count) {
    throw py::index_error(std::string(argument) + " index " + std::to_string(index) +
                          " is out of range: the model has " + count_name + " = " +
                          std::to_string(count) + " (0 to " + std::to_string(count - 1) + ")");
  }
}

void BindModel(py::module_& m) {
  BindModelClass(m);
  BindForces(m);
  BindConstraints(m);
  BindContacts(m);
  BindState(m);
}

}  // namespace chasles::python
