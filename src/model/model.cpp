#include "chasles/model/model.h"

#include <atomic>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

std::uint64_t ModelIdentity::Next() noexcept {
  static std::atomic<std::uint64_t> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed) + 1;
}

BodyIndex Model::AddBody(std::string name, const MassProperties& mass_properties) {
  if (name.empty()) throw InputError("a body needs a non-empty name");
  for (const Body& b : bodies_) {
    if (b.name() == name) {
      throw InputError(
          fmt::format("body '{}' is defined twice; give each body its own name", name));
    }
  }
  bodies_.emplace_back(std::move(name), mass_properties);
  id_.Renew();
  return num_bodies() - 1;
}

int Model::AddForceElement(std::shared_ptr<const ForceElement> element) {
  if (!element) throw InputError("force element is null");
  for (const auto& f : forces_) {
    if (f->name() == element->name()) {
      throw InputError(
          fmt::format("force element '{}' is defined twice; give each force element its own name",
                      element->name()));
    }
  }
  for (BodyIndex b : element->bodies()) {
    if (b < 0 || b >= num_bodies()) {
      throw InputError(fmt::format(
          "force element '{}' acts on body index {}, but the model has {} bodies (0 to {})",
          element->name(), b, num_bodies(), num_bodies() - 1));
    }
  }
  forces_.push_back(std::move(element));
  id_.Renew();
  return num_force_elements() - 1;
}

int Model::AddConstraint(std::shared_ptr<const Constraint> constraint) {
  if (!constraint) throw InputError("constraint is null");
  for (const auto& c : constraints_) {
    if (c->name() == constraint->name()) {
      throw InputError(fmt::format(
          "constraint '{}' is defined twice; give each constraint its own name", c->name()));
    }
  }
  for (BodyIndex b : {constraint->parent(), constraint->child()}) {
    if (b == kWorld) continue;
    if (b < 0 || b >= num_bodies()) {
      throw InputError(fmt::format(
          "constraint '{}' acts on body index {}, but the model has {} bodies (0 to {}); use "
          "kWorld ({}) for the ground",
          constraint->name(), b, num_bodies(), num_bodies() - 1, kWorld));
    }
  }
  const int rows = constraint->num_rows();
  if (rows < 1 || rows > kMaxConstraintRows) {
    throw InputError(fmt::format("constraint '{}' has {} rows; 1 to {} are supported",
                                 constraint->name(), rows, kMaxConstraintRows));
  }
  row_offsets_.push_back(num_constraint_rows_);
  num_constraint_rows_ += rows;
  constraints_.push_back(std::move(constraint));
  id_.Renew();
  return num_constraints() - 1;
}

int Model::FindConstraint(std::string_view name) const {
  std::string known;
  for (int i = 0; i < num_constraints(); ++i) {
    if (constraint(i).name() == name) return i;
    known += (i ? ", " : "") + constraint(i).name();
  }
  throw InputError(fmt::format("no constraint named '{}'; the constraints are: {}", name,
                               known.empty() ? "(none)" : known));
}

BodyIndex Model::FindBody(std::string_view name) const {
  std::string known;
  for (int i = 0; i < num_bodies(); ++i) {
    if (body(i).name() == name) return i;
    known += (i ? ", " : "") + body(i).name();
  }
  throw InputError(fmt::format("no body named '{}'; the bodies are: {}", name,
                               known.empty() ? "(none)" : known));
}

int Model::FindForceElement(std::string_view name) const {
  std::string known;
  for (int i = 0; i < num_force_elements(); ++i) {
    if (force_element(i).name() == name) return i;
    known += (i ? ", " : "") + force_element(i).name();
  }
  throw InputError(fmt::format("no force element named '{}'; the force elements are: {}", name,
                               known.empty() ? "(none)" : known));
}

int Model::AddContact(const ContactSpec& spec) {
  for (const Contact& c : contacts_) {
    if (c.name() == spec.name) {
      throw InputError(
          fmt::format("contact '{}' is defined twice; give each contact its own name", spec.name));
    }
  }
  contacts_.emplace_back(*this, spec);
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
  std::string known;
  for (int i = 0; i < num_contacts(); ++i) {
    if (contact(i).name() == name) return i;
    known += (i ? ", " : "") + contact(i).name();
  }
  throw InputError(fmt::format("no contact named '{}'; the contacts are: {}", name,
                               known.empty() ? "(none)" : known));
}

}  // namespace chasles
