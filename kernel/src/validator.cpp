#include "validator.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <set>
#include <vector>

#include "talus/error.hpp"
#include "text.hpp"

namespace talus {

namespace {

using nlohmann::json;

// A value as an error message quotes it: short, and never the whole of a
// large or deeply nested one.
std::string describe(const json& j) {
  constexpr std::size_t shown = 37;
  switch (j.type()) {
    case json::value_t::string: {
      const auto& s = j.get_ref<const std::string&>();
      return "the string " + json(s.substr(0, shown)).dump() + (s.size() > shown ? "..." : "");
    }
    case json::value_t::boolean: return "the boolean " + j.dump();
    case json::value_t::null: return "null";
    case json::value_t::array: {
      const bool flat = std::none_of(j.begin(), j.end(), [](const json& e) { return e.is_structured(); });
      std::string s = flat && j.size() <= 8 ? j.dump() : "";
      if (s.empty() || s.size() > shown + 3) return "an array of " + std::to_string(j.size()) + " values";
      return "an array " + s;
    }
    case json::value_t::object: return "an object";
    default: return j.dump();
  }
}

std::vector<std::string> names_of(const ParamSet& set) {
  std::vector<std::string> out;
  for (const auto& s : set.specs()) out.push_back(s.name);
  std::sort(out.begin(), out.end());
  return out;
}

std::string known_hint(const std::string& word, const std::vector<std::string>& known) {
  const std::string guess = text::closest(word, known);
  std::string hint = guess.empty() ? "" : "did you mean '" + guess + "'?  ";
  return hint + "known: " + (known.empty() ? "(none)" : text::join(known));
}

class Validator {
 public:
  explicit Validator(ValidationContext& c) : c_(c) {}

  // `skip` is the model-selector key ("type"), validated by the caller.
  ParamValues object(const ParamSet& set, const json& j, const std::string& ptr, std::string_view owner,
                     const ParamSet* extra = nullptr, std::string_view skip = {}) {
    ParamValues out(c_.file, ptr);
    if (!j.is_object()) {
      error(ptr, "expected an object, got " + describe(j));
      return out;
    }
    const std::size_t errors_before = c_.diagnostics->size();
    // Unknown keys first, so a misspelt key and its "missing" twin read together.
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (set.find(it.key()) || (extra && extra->find(it.key())) || (!skip.empty() && it.key() == skip)) continue;
      std::vector<std::string> known = names_of(set);
      if (extra)
        for (auto& n : names_of(*extra)) known.push_back(n);
      std::sort(known.begin(), known.end());
      const std::string where = owner.empty() ? (set.name().empty() ? "here" : "in " + set.name()) : std::string(owner);
      error(ptr + "/" + text::pointer_token(it.key()),
            "unknown parameter " + (owner.empty() ? where : "for " + where), known_hint(it.key(), known));
    }
    for (const ParamSet* s : {&set, extra}) {
      if (!s) continue;
      for (const auto& spec : s->specs()) {
        const std::string p = ptr + "/" + text::pointer_token(spec.name);
        auto it = j.find(spec.name);
        if (it == j.end()) {
          ParamValue v;
          if (fill_default(spec, v))
            out.set(spec.name, std::move(v));
          else if (spec.required)
            error(p, "missing required parameter" + (spec.doc.empty() ? "" : " (" + spec.doc + ")"));
          continue;
        }
        ParamValue v;
        if (value(spec, *it, p, v)) out.set(spec.name, std::move(v));
      }
    }
    if (c_.diagnostics->size() == errors_before)
      for (const auto& check : set.checks()) check(out, *c_.diagnostics);
    return out;
  }

 private:
  void error(const std::string& ptr, std::string message, std::string hint = {}) {
    c_.diagnostics->error(c_.file, ptr, std::move(message), std::move(hint));
  }

  bool fill_default(const ParamSpec& s, ParamValue& v) {
    v.type = s.type;
    switch (s.type) {
      case ParamType::real:
        if (!s.default_real) return false;
        v.real = *s.default_real;
        return true;
      case ParamType::integer:
        if (!s.default_integer) return false;
        v.integer = *s.default_integer;
        return true;
      case ParamType::boolean:
        if (!s.default_boolean) return false;
        v.boolean = *s.default_boolean;
        return true;
      case ParamType::string:
      case ParamType::choice:
      case ParamType::path:
        if (!s.default_string) return false;
        v.text = *s.default_string;
        return true;
      case ParamType::vector: {
        const auto& d = (c_.dim == 2 && s.default_reals_2d) ? s.default_reals_2d : s.default_reals;
        if (!d) return false;
        v.reals = *d;
        v.reals.resize(3, 0.0);
        return true;
      }
      case ParamType::real_list:
        if (s.default_reals) v.reals = *s.default_reals;
        return s.default_reals.has_value() || !s.required;
      case ParamType::vector_list:
      case ParamType::string_list:
      case ParamType::index_lists:
      case ParamType::json_list:
      case ParamType::object_list:
      case ParamType::object_map:
        return !s.required;  // an optional list is an empty list
      case ParamType::object:
        // An optional object whose members all have defaults is filled in.
        if (s.required || !s.nested) return false;
        for (const auto& m : s.nested->specs())
          if (m.required) return false;
        {
          Diagnostics ignored;
          ValidationContext quiet = c_;
          quiet.diagnostics = &ignored;
          Validator inner(quiet);
          v.objects.push_back(inner.object(*s.nested, json::object(), "", {}));
        }
        return true;
      case ParamType::model_list:
        return !s.required;
      case ParamType::one_of:
      case ParamType::model:
        return false;
    }
    return false;
  }

  bool in_range(const ParamSpec& s, double x, const std::string& p) {
    const bool low_ok = s.lower_inclusive ? x >= s.lower : x > s.lower;
    const bool high_ok = s.upper_inclusive ? x <= s.upper : x < s.upper;
    if (low_ok && high_ok) return true;
    error(p, text::number(x) + " is out of range; " + s.range_text());
    return false;
  }

  bool number(const json& j, const std::string& p, double& x) {
    if (!j.is_number()) {
      error(p, "expected a number, got " + describe(j));
      return false;
    }
    x = j.get<double>();
    return true;
  }

  bool numbers(const ParamSpec& s, const json& j, const std::string& p, std::size_t count, std::vector<double>& out) {
    if (!j.is_array() || (count && j.size() != count)) {
      error(p, "expected " + (count ? "an array of " + std::to_string(count) + " numbers" : std::string("an array of numbers")) +
                   ", got " + describe(j));
      return false;
    }
    bool ok = true;
    for (std::size_t k = 0; k < j.size(); ++k) {
      double x = 0;
      const std::string pk = p + "/" + std::to_string(k);
      if (number(j[k], pk, x) && in_range(s, x, pk))
        out.push_back(x);
      else
        ok = false;
    }
    return ok;
  }

  bool value(const ParamSpec& s, const json& j, const std::string& p, ParamValue& v) {
    v.type = s.type;
    switch (s.type) {
      case ParamType::real:
        return number(j, p, v.real) && in_range(s, v.real, p);
      case ParamType::integer: {
        double x = 0;
        if (!j.is_number() || !number(j, p, x) || std::floor(x) != x) {
          error(p, "expected an integer, got " + describe(j));
          return false;
        }
        // Beyond 2^63 the conversion to int64 is undefined; no count or index is that large.
        if (!(std::abs(x) < 0x1p63)) {
          error(p, text::number(x) + " is out of range; an integer here must lie within +-9.2e18");
          return false;
        }
        if (!in_range(s, x, p)) return false;
        // Exactly as written when the text is an integer (a double keeps only 53 bits).
        v.integer = j.is_number_unsigned()  ? static_cast<std::int64_t>(j.get<std::uint64_t>())
                    : j.is_number_integer() ? j.get<std::int64_t>()
                                            : static_cast<std::int64_t>(x);
        return true;
      }
      case ParamType::boolean:
        if (!j.is_boolean()) {
          error(p, "expected true or false, got " + describe(j));
          return false;
        }
        v.boolean = j.get<bool>();
        return true;
      case ParamType::string:
        if (!j.is_string()) {
          error(p, "expected a string, got " + describe(j));
          return false;
        }
        v.text = j.get<std::string>();
        return true;
      case ParamType::choice:
        if (!j.is_string()) {
          error(p, "expected one of " + text::join(s.choices) + ", got " + describe(j));
          return false;
        }
        v.text = j.get<std::string>();
        if (std::find(s.choices.begin(), s.choices.end(), v.text) == s.choices.end()) {
          error(p, "'" + v.text + "' is not allowed", known_hint(v.text, s.choices));
          return false;
        }
        return true;
      case ParamType::path: {
        if (!j.is_string() || j.get<std::string>().empty()) {
          error(p, "expected a file name, got " + describe(j));
          return false;
        }
        if (j.get<std::string>().find('\0') != std::string::npos) {
          error(p, "a file name cannot hold a NUL byte, got " + describe(j));
          return false;
        }
        std::filesystem::path path = j.get<std::string>();
        if (c_.path_pointers) c_.path_pointers->push_back(p);
        if (path.is_relative()) path = std::filesystem::path(c_.base_dir) / path;
        v.text = path.lexically_normal().string();
        // The error_code form: a name too long for the system throws otherwise.
        std::error_code ec;
        if (!std::filesystem::exists(v.text, ec)) {
          error(p, ec ? "cannot look up " + describe(j) + " (" + ec.message() + ")" : "file not found: " + v.text);
          return false;
        }
        return true;
      }
      case ParamType::vector: {
        const std::size_t n = s.length ? static_cast<std::size_t>(s.length) : static_cast<std::size_t>(c_.dim);
        if (!numbers(s, j, p, n, v.reals)) return false;
        v.reals.resize(3, 0.0);
        return true;
      }
      case ParamType::real_list:
        return numbers(s, j, p, 0, v.reals);
      case ParamType::vector_list: {
        if (!j.is_array()) {
          error(p, "expected an array of points, got " + describe(j));
          return false;
        }
        const std::size_t n = s.length ? static_cast<std::size_t>(s.length) : static_cast<std::size_t>(c_.dim);
        bool ok = true;
        for (std::size_t k = 0; k < j.size(); ++k) {
          std::vector<double> point;
          if (numbers(s, j[k], p + "/" + std::to_string(k), n, point)) {
            point.resize(3, 0.0);
            v.reals.insert(v.reals.end(), point.begin(), point.end());
          } else {
            ok = false;
          }
        }
        return ok;
      }
      case ParamType::string_list: {
        if (!j.is_array()) {
          error(p, "expected an array of strings, got " + describe(j));
          return false;
        }
        bool ok = true;
        for (std::size_t k = 0; k < j.size(); ++k) {
          const std::string pk = p + "/" + std::to_string(k);
          if (!j[k].is_string()) {
            error(pk, "expected a string, got " + describe(j[k]));
            ok = false;
            continue;
          }
          const std::string item = j[k].get<std::string>();
          if (!s.choices.empty() && std::find(s.choices.begin(), s.choices.end(), item) == s.choices.end()) {
            error(pk, "'" + item + "' is not allowed", known_hint(item, s.choices));
            ok = false;
          }
          v.strings.push_back(item);
        }
        return ok;
      }
      case ParamType::json_list:
        if (!j.is_array()) {
          error(p, "expected an array, got " + describe(j));
          return false;
        }
        for (const auto& item : j) v.strings.push_back(item.dump());
        return true;
      case ParamType::index_lists: {
        bool ok = j.is_array();
        for (std::size_t k = 0; ok && k < j.size(); ++k) {
          std::vector<int> list;
          ok = j[k].is_array();
          for (std::size_t m = 0; ok && m < j[k].size(); ++m) {
            // Read as a wide integer first: get<int>() would take 4294967297 for 1.
            const json& index = j[k][m];
            ok = index.is_number_unsigned() ? index.get<std::uint64_t>() <= std::numeric_limits<int>::max()
                                            : index.is_number_integer() && index.get<std::int64_t>() >= 0 &&
                                                  index.get<std::int64_t>() <= std::numeric_limits<int>::max();
            if (ok) list.push_back(static_cast<int>(index.get<std::int64_t>()));
          }
          if (!ok)
            error(p + "/" + std::to_string(k), "expected an array of vertex indices (integers from 0 to " +
                                                   std::to_string(std::numeric_limits<int>::max()) + ")");
          v.indices.push_back(std::move(list));
        }
        if (!j.is_array()) error(p, "expected an array of arrays of vertex indices, got " + describe(j));
        return ok;
      }
      case ParamType::object:
        v.objects.push_back(object(*s.nested, j, p, {}));
        return true;
      case ParamType::object_list: {
        if (!j.is_array()) {
          error(p, "expected an array of objects, got " + describe(j));
          return false;
        }
        for (std::size_t k = 0; k < j.size(); ++k)
          v.objects.push_back(object(*s.nested, j[k], p + "/" + std::to_string(k), {}));
        return true;
      }
      case ParamType::object_map: {
        if (!j.is_object()) {
          error(p, "expected an object of named entries, got " + describe(j));
          return false;
        }
        for (auto it = j.begin(); it != j.end(); ++it) {
          v.strings.push_back(it.key());
          v.objects.push_back(object(*s.nested, it.value(), p + "/" + text::pointer_token(it.key()), {}));
        }
        return true;
      }
      case ParamType::one_of: {
        std::vector<std::string> names;
        for (const auto& [n, set] : s.alternatives) names.push_back(n);
        if (!j.is_object() || j.size() != 1) {
          error(p, "expected an object with exactly one of: " + text::join(names) + ", got " + describe(j));
          return false;
        }
        const std::string key = j.begin().key();
        for (const auto& [n, set] : s.alternatives)
          if (n == key) {
            v.text = key;
            v.objects.push_back(object(*set, j.begin().value(), p + "/" + text::pointer_token(key), {}));
            return true;
          }
        error(p + "/" + text::pointer_token(key), "unknown " + s.name + " '" + key + "'", known_hint(key, names));
        return false;
      }
      case ParamType::model: {
        std::string name;
        ParamValues params;
        if (!model(s, j, p, name, params)) return false;
        v.text = std::move(name);
        v.objects.push_back(std::move(params));
        return true;
      }
      case ParamType::model_list: {
        if (!j.is_array()) {
          error(p, "expected an array of " + s.model_kind + " entries, got " + describe(j));
          return false;
        }
        bool ok = true;
        for (std::size_t k = 0; k < j.size(); ++k) {
          std::string name;
          ParamValues params;
          if (model(s, j[k], p + "/" + std::to_string(k), name, params)) {
            v.strings.push_back(std::move(name));
            v.objects.push_back(std::move(params));
          } else {
            ok = false;
          }
        }
        return ok;
      }
    }
    return false;
  }

  // A model object: {"type": NAME, ...its parameters...}.
  bool model(const ParamSpec& s, const json& j, const std::string& p, std::string& name, ParamValues& params) {
    if (!j.is_object()) {
      error(p, "expected an object with \"" + s.model_key + "\": the " + s.model_kind + " model, got " + describe(j));
      return false;
    }
    const std::vector<std::string> known = c_.models ? c_.models->model_names(s.model_kind) : std::vector<std::string>{};
    auto it = j.find(s.model_key);
    const std::string kp = p + "/" + text::pointer_token(s.model_key);
    if (it == j.end() || !it->is_string()) {
      error(it == j.end() ? p : kp, "expected \"" + s.model_key + "\": the name of a " + s.model_kind + " model",
            "known: " + text::join(known));
      return false;
    }
    name = it->get<std::string>();
    const ParamSet* set = nullptr;
    try {
      set = c_.models ? c_.models->model_params(s.model_kind, name) : nullptr;
    } catch (const InputError& e) {
      std::string what = e.what();
      if (what.rfind("error: ", 0) == 0) what.erase(0, 7);
      error(kp, what);
      return false;
    }
    if (!set) {
      error(kp, "unknown " + s.model_kind + " '" + name + "'", known_hint(name, known));
      return false;
    }
    params = object(*set, j, p, s.model_kind + " '" + name + "'", s.nested.get(), s.model_key);
    return true;
  }

  ValidationContext& c_;
};

}  // namespace

ParamValues validate(const ParamSet& set, const json& j, const std::string& pointer, ValidationContext& context,
                     std::string_view owner) {
  Validator v(context);
  return v.object(set, j, pointer, owner);
}

namespace {

// Follows the parser through objects and arrays to refuse a key given twice in
// one object (the parser would keep the last value and drop the first without
// a word: a scene with two "dp" would run with the second), and nesting deeper
// than any scene needs (what follows would recurse through it).
class ParseChecks {
 public:
  explicit ParseChecks(const std::string& file) : file_(file) {}
  static constexpr std::size_t deepest = 64;

  bool operator()(int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        element();
        if (frames_.size() >= deepest)
          throw InputError("error: " + file_ + ": " + pointer() + ": nested deeper than " + std::to_string(deepest) +
                           " levels; no scene needs that");
        frames_.push_back({event == json::parse_event_t::array_start, 0, {}, {}});
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!frames_.empty()) frames_.pop_back();
        break;
      case json::parse_event_t::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw InputError("error: " + file_ + ": " + pointer() + ": key given twice in one object; the second "
                           "value would silently replace the first: keep one");
        break;
      }
      case json::parse_event_t::value: element(); break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array;
    std::size_t index;  // array: elements begun so far
    std::string key;    // object: the key being read
    std::set<std::string> keys;
  };
  void element() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  std::string pointer() const {
    std::string p;
    for (const Frame& f : frames_)
      p += "/" + (f.array ? std::to_string(f.index - 1) : text::pointer_token(f.key));
    return p;
  }
  const std::string& file_;
  std::vector<Frame> frames_;
};

}  // namespace

json parse_json(std::string_view text, const std::string& file) {
  try {
    ParseChecks checks(file);
    return json::parse(text.begin(), text.end(), std::ref(checks), true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    // Report line and column instead of the byte offset.
    std::size_t line = 1, column = 1;
    for (std::size_t k = 0; k + 1 < e.byte && k < text.size(); ++k) {
      if (text[k] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    // "[json.exception.parse_error.101] parse error at line L, column C: REASON"; the reason may quote the
    // last token read, which can itself hold ": ".
    std::string what = e.what();
    const auto at = what.find("column ");
    const auto colon = what.find(": ", at == std::string::npos ? 0 : at);
    if (colon != std::string::npos) what = what.substr(colon + 2);
    throw InputError("error: " + file + ":" + std::to_string(line) + ":" + std::to_string(column) +
                     ": JSON syntax error: " + what);
  } catch (const json::out_of_range& e) {
    // A number beyond a double (1e999): the parser names the token; find it for the line and column.
    std::string what = e.what();
    const auto open = what.find('\''), close = what.rfind('\'');
    const std::string token = open != std::string::npos && close > open ? what.substr(open + 1, close - open - 1) : "";
    std::size_t line = 1, column = 1;
    const std::size_t at = token.empty() ? std::string_view::npos : text.find(token);
    for (std::size_t k = 0; at != std::string_view::npos && k < at; ++k) {
      if (text[k] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw InputError("error: " + file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": the number " +
                     token + " is out of range (beyond what a double holds)");
  }
}

ParamValues params_from_json(const ParamSet& set, std::string_view json_text, int dim, std::string_view file) {
  Diagnostics diagnostics;
  ValidationContext context{std::string(file), ".", dim, nullptr, &diagnostics};
  const json j = parse_json(json_text, context.file);
  ParamValues values = validate(set, j, "", context);
  if (!diagnostics.empty()) throw InputError(diagnostics.format());
  return values;
}

}  // namespace talus
