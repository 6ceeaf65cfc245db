#pragma once
/// @file
/// Force elements: everything that pushes on bodies (gravity, applied forces and moments,
/// springs, dampers, drag). Each has a name, adds its forces to the bodies it acts on, reports
/// its power for the ledger, and says whether it has a potential energy (conservative part).
/// Joints, constraints and contacts are not force elements: they come with their own solve.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "chasles/math/types.h"
#include "chasles/model/body.h"

namespace chasles {

class Model;
struct State;
struct Data;
struct ForceElementOutput;

/// A vector-valued function of the state (time state.t), e.g. a force [N] or a moment [N·m].
/// The scene layer compiles its expressions into these. It receives the Model it is evaluated
/// for and must keep no mutable state of its own: a Model is shared between threads (sweeps,
/// Python), so scratch space lives on the caller's stack or in Data.
using VectorFunction = std::function<Vec3(const Model& model, const State& state)>;

/// A scalar function of the state (time state.t), e.g. a cable's tension [N] or a joint's
/// drive torque [N·m]; the same rules as VectorFunction.
using ScalarFunction = std::function<double(const Model& model, const State& state)>;

/// In which frame a callback's vector is expressed: fixed in the world, or turning with the
/// body it acts on (a thruster).
enum class VectorFrame { kWorld, kBody };

/// One force (or pure moment) an element applied, as WrenchAccumulator::Record lists them:
/// body b, the point P it acts at (Bcm for a force at the centre of mass and for a pure
/// moment), the force and the pure moment, in W.
struct AppliedForceRecord {
  BodyIndex body = 0;
  Vec3 p_WP = Vec3::Zero();
  Vec3 F_W = Vec3::Zero();
  Vec3 M_W = Vec3::Zero();
  /// True for a pure moment (AddMoment), false for a force.
  bool is_moment = false;
};

/// Collects one element's forces into the per-body resultants of a Data, and at the same time
/// the element's own totals (sum of forces, moment about the world origin, power).
class WrenchAccumulator {
 public:
  /// Accumulates into `data` (F_Bcm_W, M_Bcm_W); reads velocities from `state` and the
  /// kinematics stage of `data`.
  WrenchAccumulator(const State& state, Data& data);

  /// Starts collecting for the element with this output record (zeroed here).
  void Begin(ForceElementOutput* output);
  /// A force F_W [N] at body b's centre of mass.
  void AddForceAtCenterOfMass(BodyIndex b, const Vec3& F_W);
  /// A force F_W [N] at a point P of body b, given by its offset p_BcmP_W from Bcm in W [m].
  void AddForceAtPoint(BodyIndex b, const Vec3& p_BcmP_W, const Vec3& F_W);
  /// A pure moment M_W [N·m] on body b.
  void AddMoment(BodyIndex b, const Vec3& M_W);
  /// Power of everything this element has added so far [W].
  double power() const;
  /// Also lists every force and moment added from now on in `records` (nullptr: none, the
  /// default); for drawing them (the browser report), not for the dynamics.
  void Record(std::vector<AppliedForceRecord>* records) { records_ = records; }

 private:
  const State& state_;
  Data& data_;
  ForceElementOutput* out_ = nullptr;
  std::vector<AppliedForceRecord>* records_ = nullptr;
};

class ForceElement {
 public:
  explicit ForceElement(std::string name) : name_(std::move(name)) {}
  virtual ~ForceElement() = default;
  ForceElement(const ForceElement&) = delete;
  ForceElement& operator=(const ForceElement&) = delete;

  /// Name used in reports and messages.
  const std::string& name() const { return name_; }

  /// Adds this element's forces at `state` (the kinematics stage of `data` is filled) and
  /// returns the power of its non-conservative part [W].
  virtual double AddForces(const Model& model, const State& state, const Data& data,
                           WrenchAccumulator& out) const = 0;
  /// True when part or all of it derives from a potential energy.
  virtual bool has_potential() const { return false; }
  /// Its potential energy at `state` [J] (0 when it has none).
  virtual double CalcPotentialEnergy(const Model& /*model*/, const State& /*state*/) const {
    return 0.0;
  }
  /// True when its non-conservative work can only remove energy (dampers, drag).
  virtual bool is_dissipative() const { return false; }
  /// Bodies it acts on (kWorld excluded), checked by Model::AddForceElement.
  virtual std::vector<BodyIndex> bodies() const = 0;
  /// The same element acting on the bodies renumbered by `new_index` (new_index[b] is body b's
  /// index in another Model holding the same bodies; kWorld stays kWorld), for splitting a
  /// Model into independent islands; nullptr when it cannot be renumbered (an element that
  /// evaluates user functions of the whole State, which may read any body). An element whose
  /// bodies() is empty acts on each body of the Model alone (gravity) and is copied into every
  /// island.
  virtual std::shared_ptr<const ForceElement> Renumbered(
      const std::vector<BodyIndex>& /*new_index*/) const {
    return nullptr;
  }

 private:
  std::string name_;
};

}  // namespace chasles
