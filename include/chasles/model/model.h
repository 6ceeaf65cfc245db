#pragma once
/// @file
/// Model: the bodies and force elements of a system, built once and then only read (it is
/// passed as `const Model&` to every algorithm). Maximal coordinates: each body moves freely
/// unless a constraint (joint, rolling contact, prescribed motion) holds it.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "chasles/model/body.h"
#include "chasles/model/constraint.h"
#include "chasles/model/contact.h"
#include "chasles/model/force_element.h"

namespace chasles {

/// Name → index table for one kind of Model element, so that adding n elements (each checked
/// for a duplicate name) and finding one by name cost O(n) and O(1) on average instead of
/// O(n²) and O(n). Looks up by std::string_view without building a std::string.
class NameIndex {
 public:
  /// Index of `name`, or -1 when absent.
  int Find(std::string_view name) const {
    const auto it = map_.find(name);
    return it == map_.end() ? -1 : it->second;
  }
  /// Records `name` → `index`; false (and nothing recorded) when `name` is already present.
  bool Insert(const std::string& name, int index) { return map_.emplace(name, index).second; }
  /// Forgets `name` (undoes an Insert whose element was then refused).
  void Erase(const std::string& name) { map_.erase(name); }

 private:
  struct Hash {
    using is_transparent = void;
    size_t operator()(std::string_view s) const noexcept {
      return std::hash<std::string_view>{}(s);
    }
  };
  std::unordered_map<std::string, int, Hash, std::equal_to<>> map_;
};

/// The identity of a Model object (Model::id()): unique among the Models of the process. A
/// copy is another Model and gets a new identity; a move hands the identity over and gives
/// the moved-from Model a new one.
class ModelIdentity {
 public:
  ModelIdentity() : value_(Next()) {}
  ModelIdentity(const ModelIdentity&) : value_(Next()) {}
  ModelIdentity(ModelIdentity&& other) noexcept : value_(other.value_) { other.value_ = Next(); }
  ModelIdentity& operator=(const ModelIdentity& other) {
    if (this != &other) value_ = Next();
    return *this;
  }
  ModelIdentity& operator=(ModelIdentity&& other) noexcept {
    if (this != &other) {
      value_ = other.value_;
      other.value_ = Next();
    }
    return *this;
  }
  std::uint64_t value() const { return value_; }
  /// A new identity (the Model changed).
  void Renew() { value_ = Next(); }

 private:
  /// The next value of a process-wide counter (thread-safe; never 0).
  static std::uint64_t Next() noexcept;
  std::uint64_t value_;
};

class Model {
 public:
  /// Identity of this Model: a Data made by MakeData(model) stores it, and every algorithm
  /// that takes (model, ..., data) checks that they match (see data.h). It is new for every
  /// Model constructed or copied, kept by a move, and renewed by every Add* (a Data sized
  /// before a body, force element, constraint or contact was added no longer fits).
  std::uint64_t id() const { return id_.value(); }

  /// Adds a free body; returns its index. Throws InputError for a duplicate or empty name or
  /// invalid mass properties (see Body).
  BodyIndex AddBody(std::string name, const MassProperties& mass_properties);
  /// Adds a force element; returns its index. Throws InputError for a duplicate name or a body
  /// index that does not exist.
  int AddForceElement(std::shared_ptr<const ForceElement> element);

  /// Number of bodies.
  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  /// Body `b` (0 <= b < num_bodies()).
  const Body& body(BodyIndex b) const { return bodies_[static_cast<size_t>(b)]; }
  /// Number of force elements.
  int num_force_elements() const { return static_cast<int>(forces_.size()); }
  /// Force element `i`.
  const ForceElement& force_element(int i) const { return *forces_[static_cast<size_t>(i)]; }
  /// Adds a constraint (joint, rolling contact, driver); returns its index. Throws InputError
  /// for a duplicate name or a body index that does not exist.
  int AddConstraint(std::shared_ptr<const Constraint> constraint);
  /// Number of constraints.
  int num_constraints() const { return static_cast<int>(constraints_.size()); }
  /// Constraint `i`.
  const Constraint& constraint(int i) const { return *constraints_[static_cast<size_t>(i)]; }
  /// Total number of constraint rows (multipliers).
  int num_constraint_rows() const { return num_constraint_rows_; }
  /// First row of constraint `i` in the stacked system.
  int constraint_row_offset(int i) const { return row_offsets_[static_cast<size_t>(i)]; }
  /// Index of the constraint called `name`; InputError otherwise.
  int FindConstraint(std::string_view name) const;
  /// Index of the body called `name`; InputError listing the known names otherwise.
  BodyIndex FindBody(std::string_view name) const;
  /// Index of the force element called `name`; InputError otherwise.
  int FindForceElement(std::string_view name) const;
  /// Adds a unilateral contact (see contact.h); returns its index. Throws InputError for a
  /// duplicate name or an invalid spec (see Contact).
  int AddContact(const ContactSpec& spec);
  /// Number of contacts.
  int num_contacts() const { return static_cast<int>(contacts_.size()); }
  /// Contact `i`.
  const Contact& contact(int i) const { return contacts_[static_cast<size_t>(i)]; }
  /// Total number of contact points over all contacts (State::contacts has one entry each).
  int num_contact_points() const { return num_contact_points_; }
  /// Index of contact `i`'s first point among all contact points.
  int contact_point_offset(int i) const { return contact_offsets_[static_cast<size_t>(i)]; }
  /// The contact owning contact point `p`.
  int contact_of_point(int p) const { return point_owner_[static_cast<size_t>(p)]; }
  /// Name of contact point `p` (see Contact::point_name).
  std::string contact_point_name(int p) const;
  /// Index of the contact called `name`; InputError listing the known names otherwise.
  int FindContact(std::string_view name) const;

 private:
  std::vector<Body> bodies_;
  NameIndex body_names_;
  std::vector<std::shared_ptr<const ForceElement>> forces_;
  NameIndex force_names_;
  std::vector<std::shared_ptr<const Constraint>> constraints_;
  NameIndex constraint_names_;
  std::vector<int> row_offsets_;
  int num_constraint_rows_ = 0;
  std::vector<Contact> contacts_;
  NameIndex contact_names_;
  std::vector<int> contact_offsets_;
  std::vector<int> point_owner_;
  int num_contact_points_ = 0;
  ModelIdentity id_;
};

}  // namespace chasles
