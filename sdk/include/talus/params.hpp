// Declared parameters (DESIGN.md principle 4). A model declares its parameters
// once in a ParamSet; from that declaration the host validates scenes (every
// error with its JSON pointer), generates the JSON Schema, `talus doc` and
// `talus example`. Factories receive the validated, typed ParamValues and never
// see raw JSON.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "talus/config.hpp"
#include "talus/error.hpp"
#include "talus/vec3.hpp"

namespace talus {

enum class ParamType {
  real,         // a number, optionally with a unit and a range
  integer,      // a whole number
  boolean,
  string,       // free text (a name)
  choice,       // one of a fixed list of strings
  path,         // a file name, relative to the scene file
  vector,       // a point or direction: `dim` numbers (or a fixed count)
  real_list,    // any number of numbers
  vector_list,  // a list of points
  string_list,  // a list of strings (optionally restricted to choices)
  index_lists,  // a list of lists of non-negative integers (polyhedron faces)
  json_list,    // a list of any JSON values, each kept as its compact text (a study's axis values)
  object,       // a nested object with its own ParamSet
  object_list,  // an array of such objects
  object_map,   // an object whose keys are user-chosen names
  one_of,       // an object with exactly one key naming an alternative
  model,        // a plugin model of a given kind, selected by a key ("type")
  model_list,   // an array of such models (the pipeline, the outputs)
};

TALUS_API const char* to_string(ParamType type);

class ParamSet;
class ParamValues;
class Diagnostics;

// One declared parameter. Built with the chaining setters of ParamBuilder.
struct TALUS_API ParamSpec {
  std::string name;
  ParamType type = ParamType::real;
  std::string unit;  // SI unit text, empty for dimensionless
  std::string doc;   // one line
  bool required = true;

  // Defaults (only the one matching `type` is used).
  std::optional<double> default_real;
  std::optional<std::int64_t> default_integer;
  std::optional<bool> default_boolean;
  std::optional<std::string> default_string;
  std::optional<std::vector<double>> default_reals;  // vector / real_list
  // Scene-dimension-dependent default of a vector: used when dim == 2.
  std::optional<std::vector<double>> default_reals_2d;

  // Ranges for real and integer (and each element of vector/real_list).
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool lower_inclusive = true;
  bool upper_inclusive = true;

  std::vector<std::string> choices;  // choice, string_list (empty = any)
  int length = 0;                    // vector: 0 means the scene dimension
  std::shared_ptr<const ParamSet> nested;  // object, object_list, object_map; model(_list): keys every model accepts
  std::vector<std::pair<std::string, std::shared_ptr<const ParamSet>>> alternatives;  // one_of
  std::string model_kind;            // model: "eos", "rheology", ...
  std::string model_key = "type";    // model: key naming the model

  bool has_range() const;
  std::string range_text() const;  // e.g. "must be > 0"
};

// Chaining setters returned by the ParamSet builders.
class TALUS_API ParamBuilder {
 public:
  explicit ParamBuilder(ParamSpec& spec) : spec_(&spec) {}
  ParamBuilder& unit(std::string u);
  ParamBuilder& doc(std::string d);
  // May be absent, with no default: has() is then false. Exception: an
  // optional list (real_list, vector_list, string_list, index_lists,
  // object_list, object_map, model_list) is always present, empty if absent.
  ParamBuilder& optional();
  ParamBuilder& default_value(double v);
  ParamBuilder& default_value(int v);
  ParamBuilder& default_value(std::int64_t v);
  ParamBuilder& default_value(bool v);
  ParamBuilder& default_value(const char* v);
  ParamBuilder& default_value(std::string v);
  ParamBuilder& default_value(std::vector<double> v);
  // For vectors whose default depends on the scene dimension (e.g. gravity).
  ParamBuilder& default_value(std::vector<double> in_3d, std::vector<double> in_2d);
  ParamBuilder& min(double v);            // >= v
  ParamBuilder& max(double v);            // <= v
  ParamBuilder& greater_than(double v);   // > v
  ParamBuilder& less_than(double v);      // < v
  ParamBuilder& length(int n);            // vector: fixed number of components
  ParamBuilder& key(std::string k);       // model: selector key, default "type"
  ParamBuilder& alternative(std::string name, ParamSet set);  // one_of

 private:
  ParamSpec* spec_;
};

// The declared parameters of one model (or one section of a scene).
class TALUS_API ParamSet {
 public:
  using Check = std::function<void(const ParamValues&, Diagnostics&)>;

  ParamSet() = default;
  ParamSet(std::string name, std::string summary);

  ParamBuilder real(std::string name);
  ParamBuilder integer(std::string name);
  ParamBuilder boolean(std::string name);
  ParamBuilder string(std::string name);
  ParamBuilder choice(std::string name, std::vector<std::string> choices);
  ParamBuilder path(std::string name);
  ParamBuilder vector(std::string name);
  ParamBuilder real_list(std::string name);
  ParamBuilder vector_list(std::string name);
  ParamBuilder string_list(std::string name, std::vector<std::string> choices = {});
  ParamBuilder index_lists(std::string name);
  ParamBuilder json_list(std::string name);
  ParamBuilder object(std::string name, ParamSet nested);
  ParamBuilder object_list(std::string name, ParamSet nested);
  ParamBuilder object_map(std::string name, ParamSet nested);
  ParamBuilder one_of(std::string name);
  ParamBuilder model(std::string name, std::string kind, ParamSet common = {});
  // `common`: keys every model in this slot accepts besides its own (e.g. an
  // output's "every"); they are validated and passed to the factory too.
  ParamBuilder model_list(std::string name, std::string kind, ParamSet common = {});

  // A semantic check run after the structure validated (phase 4): it may
  // report errors through Diagnostics with the values' JSON pointers.
  void check(Check fn) { checks_.push_back(std::move(fn)); }

  const std::string& name() const { return name_; }
  const std::string& summary() const { return summary_; }
  const std::vector<ParamSpec>& specs() const { return specs_; }
  const std::vector<Check>& checks() const { return checks_; }
  const ParamSpec* find(std::string_view name) const;

 private:
  ParamBuilder add(std::string name, ParamType type);

  std::string name_;
  std::string summary_;
  std::vector<ParamSpec> specs_;
  std::vector<Check> checks_;
};

// A validated value. Which members are meaningful depends on `type`.
struct TALUS_API ParamValue {
  // Defined after ParamValues: otherwise clang 14 instantiates
  // std::pair<std::string, ParamValue> while checking this constructor inside
  // ParamValues, where the pair is still incomplete.
  ParamValue();

  ParamType type = ParamType::real;
  double real = 0.0;
  std::int64_t integer = 0;
  bool boolean = false;
  std::string text;                  // string, choice, path (resolved), model name, one_of alternative
  std::vector<double> reals;         // vector (always 3 long, z = 0 in 2D), real_list, vector_list (3 per point)
  std::vector<std::string> strings;  // string_list, json_list (compact JSON texts), object_map keys, model_list names
  std::vector<std::vector<int>> indices;  // index_lists
  std::vector<ParamValues> objects;  // object, object_list, object_map, model parameters, one_of
};

// Typed, validated values of one ParamSet, with where they came from so that
// later (semantic) errors can still name the file and the JSON pointer.
class TALUS_API ParamValues {
 public:
  ParamValues() = default;
  ParamValues(std::string file, std::string pointer) : file_(std::move(file)), pointer_(std::move(pointer)) {}

  bool has(std::string_view name) const;
  double real(std::string_view name) const;
  std::int64_t integer(std::string_view name) const;
  bool boolean(std::string_view name) const;
  const std::string& string(std::string_view name) const;  // string, choice, path
  Vec3 vector(std::string_view name) const;
  const std::vector<double>& reals(std::string_view name) const;
  std::vector<Vec3> vectors(std::string_view name) const;
  const std::vector<std::string>& strings(std::string_view name) const;
  const std::vector<std::vector<int>>& index_lists(std::string_view name) const;
  const std::vector<std::string>& json_texts(std::string_view name) const;  // json_list
  const ParamValues& object(std::string_view name) const;
  const std::vector<ParamValues>& objects(std::string_view name) const;
  // object_map: names in declaration order of the file, values alongside.
  const std::vector<std::string>& keys(std::string_view name) const;
  // model: the selected model name, and its parameters.
  const std::string& model_name(std::string_view name) const;
  const ParamValues& model_params(std::string_view name) const;
  // model_list: the model names in order; objects(name) gives their parameters.
  const std::vector<std::string>& model_names(std::string_view name) const;
  // one_of: the alternative chosen and its values.
  const std::string& alternative(std::string_view name) const;
  const ParamValues& alternative_values(std::string_view name) const;

  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }
  std::string pointer(std::string_view name) const;  // pointer of a member

  // Throws InputError "FILE: POINTER/NAME: message" (for checks at setup time).
  [[noreturn]] void fail(std::string_view name, std::string_view message) const;

  // Reads the file that path parameter `name` names, with read(path). A
  // reader's InputError names only that file ("error: mesh.obj:3: ..."); it
  // is rethrown with the scene file and this parameter's JSON pointer first.
  template <class Read>
  decltype(auto) read_file(std::string_view name, Read&& read) const {
    try {
      return read(string(name));
    } catch (const InputError& e) {
      std::string_view what = e.what();
      if (what.starts_with("error: ")) what.remove_prefix(7);
      fail(name, what);
    }
  }

  // Used by the validator.
  void set(std::string name, ParamValue value);
  const ParamValue& at(std::string_view name) const;
  const std::vector<std::pair<std::string, ParamValue>>& entries() const { return entries_; }

 private:
  const ParamValue* lookup(std::string_view name) const;

  std::string file_;
  std::string pointer_;
  std::vector<std::pair<std::string, ParamValue>> entries_;
};

inline ParamValue::ParamValue() = default;

// Errors collected while validating, each with file, JSON pointer, what is
// wrong and, on a second line, what is allowed.
struct TALUS_API Diagnostic {
  std::string file;
  std::string pointer;
  std::string message;
  std::string hint;  // "did you mean ..." / "known: ..." / "allowed: ..."
};

class TALUS_API Diagnostics {
 public:
  void error(const ParamValues& where, std::string_view name, std::string message, std::string hint = {});
  void error(std::string file, std::string pointer, std::string message, std::string hint = {});
  bool empty() const { return items_.empty(); }
  std::size_t size() const { return items_.size(); }
  const std::vector<Diagnostic>& items() const { return items_; }
  // "error: FILE: POINTER: message\n       hint\n" for every item.
  std::string format() const;

 private:
  std::vector<Diagnostic> items_;
};

// Validates JSON text against a ParamSet with no model parameters to resolve
// (plugin unit tests use this to build ParamValues). Throws InputError with
// every diagnostic on bad input. `dim` sizes vector parameters.
TALUS_API ParamValues params_from_json(const ParamSet& set, std::string_view json_text, int dim = 3,
                                       std::string_view file = "<inline>");

}  // namespace talus
