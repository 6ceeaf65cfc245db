#include "chasles/model/model.h"

#include <algorithm>
#include <atomic>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/model/constraints.h"
#include "chasles/model/string_constraint.h"

namespace chasles {

std::uint64_t ModelIdentity::Next() noexcept {
  static std::atomic<std::uint64_t> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed) + 1;
}

BodyIndex Model::AddBody(std::string name, const MassProperties& mass_properties) {
  if (name.empty()) throw InputError("a body needs a non-empty name");
  if (body_names_.Find(name) >= 0) {
    throw InputError(fmt::format("body '{}' is defined twice; give each body its own name", name),
                     ErrorElement{ErrorElement::Kind::kBody, num_bodies()});
  }
  bodies_.emplace_back(std::move(name), mass_properties);
  body_names_.Insert(bodies_.back().name(), num_bodies() - 1);
  id_.Renew();
  return num_bodies() - 1;
}

int Model::AddForceElement(std::shared_ptr<const ForceElement> element) {
  if (!element) throw InputError("force element is null");
  // The element to be: its index once added.
  const ErrorElement added{ErrorElement::Kind::kForceElement, num_force_elements()};
  if (force_names_.Find(element->name()) >= 0) {
    throw InputError(
        fmt::format("force element '{}' is defined twice; give each force element its own name",
                    element->name()),
        added);
  }
  for (BodyIndex b : element->bodies()) {
    if (b < 0 || b >= num_bodies()) {
      throw InputError(
          fmt::format(
              "force element '{}' acts on body index {}, but the model has {} bodies (0 to {})",
              element->name(), b, num_bodies(), num_bodies() - 1),
          added);
    }
  }
  force_names_.Insert(element->name(), num_force_elements());
  forces_.push_back(std::move(element));
  id_.Renew();
  return num_force_elements() - 1;
}

int Model::AddConstraint(std::shared_ptr<const Constraint> constraint) {
  if (!constraint) throw InputError("constraint is null");
  // The element to be: its index once added.
  const ErrorElement added{ErrorElement::Kind::kConstraint, num_constraints()};
  if (constraint_names_.Find(constraint->name()) >= 0) {
    throw InputError(
        fmt::format("constraint '{}' is defined twice; give each constraint its own name",
                    constraint->name()),
        added);
  }
  for (BodyIndex b : {constraint->parent(), constraint->child()}) {
    if (b == kWorld) continue;
    if (b < 0 || b >= num_bodies()) {
      throw InputError(
          fmt::format(
              "constraint '{}' acts on body index {}, but the model has {} bodies (0 to {}); use "
              "kWorld ({}) for the ground",
              constraint->name(), b, num_bodies(), num_bodies() - 1, kWorld),
          added);
    }
  }
  // A particle has no orientation among its degrees of freedom (docs/design.md, "Particles and
  // slender bodies"): a joint acts on it only at its own position, and nothing that needs it
  // to turn (rolling, a gear) may hold it.
  const auto particle_attachment = [&](BodyIndex b, const AttachmentFrame& X) {
    if (b == kWorld || !body(b).is_particle()) return;
    const Vec3 d = X.p_BoJ_B - body(b).p_BoBcm_B();
    const double scale = std::max(X.p_BoJ_B.norm(), body(b).p_BoBcm_B().norm());
    if (d.norm() > 1e-9 * scale) {
      throw InputError(
          fmt::format(
              "constraint '{}': body '{}' is a point mass and the joint point is {:.6g} m from it; "
              "a point mass has no rotation to carry a point elsewhere: put the joint at the point "
              "mass, or hang the point mass from a body",
              constraint->name(), body(b).name(), d.norm()),
          added);
    }
  };
  if (const auto* joint = dynamic_cast<const Joint*>(constraint.get())) {
    particle_attachment(constraint->parent(), joint->X_PJ());
    particle_attachment(constraint->child(), joint->X_CJ());
  } else if (const auto* str = dynamic_cast<const StringConstraint*>(constraint.get())) {
    // A string pulls a point mass at its position; a drum needs a body that turns.
    for (const StringEnd* e : {&str->end_a(), &str->end_b()}) {
      if (e->body != kWorld && body(e->body).is_particle() && e->radius > 0.0) {
        throw InputError(
            fmt::format(
                "string '{}': body '{}' is a point mass, which has no drum to wind the string on; "
                "tie the string to it (radius 0) or give it a shape with inertia",
                constraint->name(), body(e->body).name()),
            added);
      }
      particle_attachment(e->body, AttachmentFrame{e->p_BoP_B, Mat3::Identity()});
    }
    for (const StringPulley& p : str->pulleys()) {
      if (p.body == kWorld) continue;
      if (p.body < 0 || p.body >= num_bodies()) {
        throw InputError(
            fmt::format(
                "string '{}': a pulley is carried by body index {}, but the model has {} bodies "
                "(0 to {}); use kWorld ({}) for a fixed pulley",
                constraint->name(), p.body, num_bodies(), num_bodies() - 1, kWorld),
            added);
      }
      particle_attachment(p.body, AttachmentFrame{p.p_BoO_B, Mat3::Identity()});
    }
  } else {
    for (BodyIndex b : {constraint->parent(), constraint->child()}) {
      if (b != kWorld && body(b).is_particle()) {
        throw InputError(
            fmt::format(
                "constraint '{}' ({}): body '{}' is a point mass, which cannot roll or turn; give "
                "it a shape with inertia",
                constraint->name(), constraint->kind(), body(b).name()),
            added);
      }
    }
  }
  const int rows = constraint->num_rows();
  if (rows < 1 || rows > kMaxConstraintRows) {
    throw InputError(fmt::format("constraint '{}' has {} rows; 1 to {} are supported",
                                 constraint->name(), rows, kMaxConstraintRows),
                     added);
  }
  constraint_names_.Insert(constraint->name(), num_constraints());
  row_offsets_.push_back(num_constraint_rows_);
  num_constraint_rows_ += rows;
  constraints_.push_back(std::move(constraint));
  id_.Renew();
  return num_constraints() - 1;
}

int Model::FindConstraint(std::string_view name) const {
  if (const int i = constraint_names_.Find(name); i >= 0) return i;
  std::string known;
  for (int i = 0; i < num_constraints(); ++i) known += (i ? ", " : "") + constraint(i).name();
  throw InputError(fmt::format("no constraint named '{}'; the constraints are: {}", name,
                               known.empty() ? "(none)" : known));
}

BodyIndex Model::FindBody(std::string_view name) const {
  if (const int i = body_names_.Find(name); i >= 0) return i;
  std::string known;
  for (int i = 0; i < num_bodies(); ++i) known += (i ? ", " : "") + body(i).name();
  throw InputError(fmt::format("no body named '{}'; the bodies are: {}", name,
                               known.empty() ? "(none)" : known));
}

int Model::FindForceElement(std::string_view name) const {
  if (const int i = force_names_.Find(name); i >= 0) return i;
  std::string known;
  for (int i = 0; i < num_force_elements(); ++i) known += (i ? ", " : "") + force_element(i).name();
  throw InputError(fmt::format("no force element named '{}'; the force elements are: {}", name,
                               known.empty() ? "(none)" : known));
}

int Model::AddContact(const ContactSpec& spec) {
  // The element to be: its index once added.
  const ErrorElement element{ErrorElement::Kind::kContact, num_contacts()};
  if (contact_names_.Find(spec.name) >= 0) {
    throw InputError(
        fmt::format("contact '{}' is defined twice; give each contact its own name", spec.name),
        element);
  }
  try {
    contacts_.emplace_back(*this, spec);
  } catch (const InputError& e) {
    RethrowForElement(e, element);
  }
  const Contact& added = contacts_.back();
  for (BodyIndex b : {added.body(), added.other_body()}) {
    if (b == kWorld || !body(b).is_particle()) continue;
    for (int k = 0; k < added.num_points(); ++k) {
      const ContactFeature& f = b == added.body() ? added.feature(k) : ContactFeature{};
      const double off = b == added.body() ? f.p_BcmF_B.norm() : added.p_OcmC_O().norm();
      const double r = b == added.body() ? f.radius : spec.other_radius;
      if (off > 0.0 || r > 0.0) {
        const std::string name = contacts_.back().name();
        contacts_.pop_back();
        throw InputError(
            fmt::format(
                "contact '{}': body '{}' is a point mass (no rotational inertia), and the contact "
                "{}; a point mass touches only at its own position: use 'points' at it, or give "
                "the body a shape (e.g. a sphere part)",
                name, body(b).name(),
                r > 0.0 ? fmt::format("has a radius of {:.6g} m", r)
                        : fmt::format("point is {:.6g} m from it", off)),
            element);
      }
    }
  }
  contact_names_.Insert(contacts_.back().name(), num_contacts() - 1);
  id_.Renew();
  contact_offsets_.push_back(num_contact_points_);
  const int n = contacts_.back().num_points();
  for (int k = 0; k < n; ++k) point_owner_.push_back(num_contacts() - 1);
  num_contact_points_ += n;
  return num_contacts() - 1;
}

std::string Model::contact_point_name(int p) const {
  const int c = contact_of_point(p);
  return contact(c).point_name(p - contact_point_offset(c));
}

int Model::FindContact(std::string_view name) const {
  if (const int i = contact_names_.Find(name); i >= 0) return i;
  std::string known;
  for (int i = 0; i < num_contacts(); ++i) known += (i ? ", " : "") + contact(i).name();
  throw InputError(fmt::format("no contact named '{}'; the contacts are: {}", name,
                               known.empty() ? "(none)" : known));
}

}  // namespace chasles
