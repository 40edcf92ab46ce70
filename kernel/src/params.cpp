// ParamSet declarations and typed access to validated ParamValues.
#include "talus/params.hpp"

#include <cmath>
#include <stdexcept>

#include "talus/error.hpp"
#include "text.hpp"

namespace talus {

const char* to_string(ParamType type) {
  switch (type) {
    case ParamType::real: return "number";
    case ParamType::integer: return "integer";
    case ParamType::boolean: return "boolean";
    case ParamType::string: return "string";
    case ParamType::choice: return "choice";
    case ParamType::path: return "file path";
    case ParamType::vector: return "vector";
    case ParamType::real_list: return "list of numbers";
    case ParamType::vector_list: return "list of points";
    case ParamType::string_list: return "list of strings";
    case ParamType::index_lists: return "list of index lists";
    case ParamType::json_list: return "list of JSON values";
    case ParamType::object: return "object";
    case ParamType::object_list: return "list of objects";
    case ParamType::object_map: return "object of named entries";
    case ParamType::one_of: return "one-of object";
    case ParamType::model: return "model";
    case ParamType::model_list: return "list of models";
  }
  return "?";
}

bool ParamSpec::has_range() const { return std::isfinite(lower) || std::isfinite(upper); }

std::string ParamSpec::range_text() const {
  std::string out;
  if (std::isfinite(lower)) out += std::string(lower_inclusive ? ">= " : "> ") + text::number(lower);
  if (std::isfinite(upper)) {
    if (!out.empty()) out += " and ";
    out += std::string(upper_inclusive ? "<= " : "< ") + text::number(upper);
  }
  return out.empty() ? out : "must be " + out;
}

ParamBuilder& ParamBuilder::unit(std::string u) { spec_->unit = std::move(u); return *this; }
ParamBuilder& ParamBuilder::doc(std::string d) { spec_->doc = std::move(d); return *this; }
ParamBuilder& ParamBuilder::optional() { spec_->required = false; return *this; }
ParamBuilder& ParamBuilder::default_value(double v) {
  spec_->required = false;
  if (spec_->type == ParamType::integer)
    spec_->default_integer = static_cast<std::int64_t>(v);
  else
    spec_->default_real = v;
  return *this;
}
ParamBuilder& ParamBuilder::default_value(int v) {
  return spec_->type == ParamType::real ? default_value(static_cast<double>(v))
                                        : default_value(static_cast<std::int64_t>(v));
}
ParamBuilder& ParamBuilder::default_value(std::int64_t v) {
  spec_->required = false;
  spec_->default_integer = v;
  return *this;
}
ParamBuilder& ParamBuilder::default_value(bool v) { spec_->required = false; spec_->default_boolean = v; return *this; }
ParamBuilder& ParamBuilder::default_value(const char* v) { return default_value(std::string(v)); }
ParamBuilder& ParamBuilder::default_value(std::string v) {
  spec_->required = false;
  spec_->default_string = std::move(v);
  return *this;
}
ParamBuilder& ParamBuilder::default_value(std::vector<double> v) {
  spec_->required = false;
  spec_->default_reals = std::move(v);
  return *this;
}
ParamBuilder& ParamBuilder::default_value(std::vector<double> in_3d, std::vector<double> in_2d) {
  spec_->required = false;
  spec_->default_reals = std::move(in_3d);
  spec_->default_reals_2d = std::move(in_2d);
  return *this;
}
ParamBuilder& ParamBuilder::min(double v) { spec_->lower = v; spec_->lower_inclusive = true; return *this; }
ParamBuilder& ParamBuilder::max(double v) { spec_->upper = v; spec_->upper_inclusive = true; return *this; }
ParamBuilder& ParamBuilder::greater_than(double v) { spec_->lower = v; spec_->lower_inclusive = false; return *this; }
ParamBuilder& ParamBuilder::less_than(double v) { spec_->upper = v; spec_->upper_inclusive = false; return *this; }
ParamBuilder& ParamBuilder::length(int n) { spec_->length = n; return *this; }
ParamBuilder& ParamBuilder::key(std::string k) { spec_->model_key = std::move(k); return *this; }
ParamBuilder& ParamBuilder::alternative(std::string name, ParamSet set) {
  spec_->alternatives.emplace_back(std::move(name), std::make_shared<const ParamSet>(std::move(set)));
  return *this;
}

ParamSet::ParamSet(std::string name, std::string summary) : name_(std::move(name)), summary_(std::move(summary)) {}

ParamBuilder ParamSet::add(std::string name, ParamType type) {
  if (find(name)) throw std::logic_error("ParamSet '" + name_ + "' declares '" + name + "' twice");
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = type;
  specs_.push_back(std::move(spec));
  return ParamBuilder(specs_.back());
}

ParamBuilder ParamSet::real(std::string name) { return add(std::move(name), ParamType::real); }
ParamBuilder ParamSet::integer(std::string name) { return add(std::move(name), ParamType::integer); }
ParamBuilder ParamSet::boolean(std::string name) { return add(std::move(name), ParamType::boolean); }
ParamBuilder ParamSet::string(std::string name) { return add(std::move(name), ParamType::string); }
ParamBuilder ParamSet::choice(std::string name, std::vector<std::string> choices) {
  auto b = add(std::move(name), ParamType::choice);
  specs_.back().choices = std::move(choices);
  return b;
}
ParamBuilder ParamSet::path(std::string name) { return add(std::move(name), ParamType::path); }
ParamBuilder ParamSet::vector(std::string name) { return add(std::move(name), ParamType::vector); }
ParamBuilder ParamSet::real_list(std::string name) { return add(std::move(name), ParamType::real_list); }
ParamBuilder ParamSet::vector_list(std::string name) { return add(std::move(name), ParamType::vector_list); }
ParamBuilder ParamSet::string_list(std::string name, std::vector<std::string> choices) {
  auto b = add(std::move(name), ParamType::string_list);
  specs_.back().choices = std::move(choices);
  return b;
}
ParamBuilder ParamSet::index_lists(std::string name) { return add(std::move(name), ParamType::index_lists); }
ParamBuilder ParamSet::json_list(std::string name) { return add(std::move(name), ParamType::json_list); }
ParamBuilder ParamSet::object(std::string name, ParamSet nested) {
  auto b = add(std::move(name), ParamType::object);
  specs_.back().nested = std::make_shared<const ParamSet>(std::move(nested));
  return b;
}
ParamBuilder ParamSet::object_list(std::string name, ParamSet nested) {
  auto b = add(std::move(name), ParamType::object_list);
  specs_.back().nested = std::make_shared<const ParamSet>(std::move(nested));
  return b;
}
ParamBuilder ParamSet::object_map(std::string name, ParamSet nested) {
  auto b = add(std::move(name), ParamType::object_map);
  specs_.back().nested = std::make_shared<const ParamSet>(std::move(nested));
  return b;
}
ParamBuilder ParamSet::one_of(std::string name) { return add(std::move(name), ParamType::one_of); }
ParamBuilder ParamSet::model(std::string name, std::string kind, ParamSet common) {
  auto b = add(std::move(name), ParamType::model);
  specs_.back().model_kind = std::move(kind);
  if (!common.specs().empty()) specs_.back().nested = std::make_shared<const ParamSet>(std::move(common));
  return b;
}

ParamBuilder ParamSet::model_list(std::string name, std::string kind, ParamSet common) {
  auto b = add(std::move(name), ParamType::model_list);
  specs_.back().model_kind = std::move(kind);
  if (!common.specs().empty()) specs_.back().nested = std::make_shared<const ParamSet>(std::move(common));
  return b;
}

const ParamSpec* ParamSet::find(std::string_view name) const {
  for (const auto& s : specs_)
    if (s.name == name) return &s;
  return nullptr;
}

// ---- ParamValues -----------------------------------------------------------

namespace {
[[noreturn]] void misuse(const ParamValues& v, std::string_view name, std::string_view what) {
  throw std::logic_error("parameter '" + std::string(name) + "' at " + v.pointer() + ": " + std::string(what));
}
}  // namespace

void ParamValues::set(std::string name, ParamValue value) {
  for (auto& [n, v] : entries_)
    if (n == name) {
      v = std::move(value);
      return;
    }
  entries_.emplace_back(std::move(name), std::move(value));
}

const ParamValue* ParamValues::lookup(std::string_view name) const {
  for (const auto& [n, v] : entries_)
    if (n == name) return &v;
  return nullptr;
}

bool ParamValues::has(std::string_view name) const { return lookup(name) != nullptr; }

const ParamValue& ParamValues::at(std::string_view name) const {
  const ParamValue* v = lookup(name);
  if (!v) misuse(*this, name, "not set (optional parameter absent, or not declared)");
  return *v;
}

double ParamValues::real(std::string_view name) const {
  const auto& v = at(name);
  if (v.type == ParamType::integer) return static_cast<double>(v.integer);
  if (v.type != ParamType::real) misuse(*this, name, "is not a number");
  return v.real;
}
std::int64_t ParamValues::integer(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::integer) misuse(*this, name, "is not an integer");
  return v.integer;
}
bool ParamValues::boolean(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::boolean) misuse(*this, name, "is not a boolean");
  return v.boolean;
}
const std::string& ParamValues::string(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::string && v.type != ParamType::choice && v.type != ParamType::path)
    misuse(*this, name, "is not a string");
  return v.text;
}
Vec3 ParamValues::vector(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::vector || v.reals.size() != 3) misuse(*this, name, "is not a vector");
  return {v.reals[0], v.reals[1], v.reals[2]};
}
const std::vector<double>& ParamValues::reals(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::real_list && v.type != ParamType::vector && v.type != ParamType::vector_list)
    misuse(*this, name, "is not a list of numbers");
  return v.reals;
}
std::vector<Vec3> ParamValues::vectors(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::vector_list) misuse(*this, name, "is not a list of points");
  std::vector<Vec3> out(v.reals.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {v.reals[3 * i], v.reals[3 * i + 1], v.reals[3 * i + 2]};
  return out;
}
const std::vector<std::string>& ParamValues::strings(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::string_list) misuse(*this, name, "is not a list of strings");
  return v.strings;
}
const std::vector<std::vector<int>>& ParamValues::index_lists(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::index_lists) misuse(*this, name, "is not a list of index lists");
  return v.indices;
}
const std::vector<std::string>& ParamValues::json_texts(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::json_list) misuse(*this, name, "is not a list of JSON values");
  return v.strings;
}
const ParamValues& ParamValues::object(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::object || v.objects.size() != 1) misuse(*this, name, "is not an object");
  return v.objects.front();
}
const std::vector<ParamValues>& ParamValues::objects(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::object_list && v.type != ParamType::object_map && v.type != ParamType::model_list)
    misuse(*this, name, "is not a list of objects");
  return v.objects;
}
const std::vector<std::string>& ParamValues::keys(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::object_map) misuse(*this, name, "is not an object of named entries");
  return v.strings;
}
const std::string& ParamValues::model_name(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::model) misuse(*this, name, "is not a model");
  return v.text;
}
const ParamValues& ParamValues::model_params(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::model || v.objects.size() != 1) misuse(*this, name, "is not a model");
  return v.objects.front();
}
const std::vector<std::string>& ParamValues::model_names(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::model_list) misuse(*this, name, "is not a list of models");
  return v.strings;
}
const std::string& ParamValues::alternative(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::one_of) misuse(*this, name, "is not a one-of object");
  return v.text;
}
const ParamValues& ParamValues::alternative_values(std::string_view name) const {
  const auto& v = at(name);
  if (v.type != ParamType::one_of || v.objects.size() != 1) misuse(*this, name, "is not a one-of object");
  return v.objects.front();
}

std::string ParamValues::pointer(std::string_view name) const { return pointer_ + "/" + text::pointer_token(name); }

void ParamValues::fail(std::string_view name, std::string_view message) const {
  throw InputError("error: " + file_ + ": " + (name.empty() ? pointer_ : pointer(name)) + ": " + std::string(message));
}

}  // namespace talus
