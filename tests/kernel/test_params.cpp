// The validator: every problem collected with its JSON pointer, messages
// pinned, defaults filled, semantic checks run only on well-formed input.
#include <gtest/gtest.h>

#include "talus/error.hpp"
#include "talus/params.hpp"
#include "validator.hpp"

namespace talus {
namespace {

ParamSet hbp_like() {
  ParamSet p{"hbp", "test rheology"};
  p.real("yield_stress").unit("Pa").min(0.0).doc("yield stress");
  p.real("viscosity").unit("Pa s").greater_than(0.0).doc("consistency");
  p.real("flow_index").greater_than(0.0).default_value(1.0).doc("n");
  p.real("regularisation").unit("s").greater_than(0.0).default_value(100.0).doc("m");
  return p;
}

// A catalogue with one kind, "rheology", holding "hbp" and "bingham".
class FakeCatalogue final : public ModelCatalogue {
 public:
  std::vector<std::string> model_names(std::string_view kind) const override {
    return kind == "rheology" ? std::vector<std::string>{"bingham", "hbp"} : std::vector<std::string>{};
  }
  const ParamSet* model_params(std::string_view kind, std::string_view name) override {
    if (kind == "rheology" && name == "hbp") return &hbp_;
    return nullptr;
  }

 private:
  ParamSet hbp_ = hbp_like();
};

ParamSet scene_like() {
  ParamSet material{"material", "a material"};
  material.real("density").unit("kg/m^3").greater_than(0.0).doc("rho0");
  material.model("rheology", "rheology").optional().doc("rheology");
  ParamSet s{"scene", "test scene"};
  s.object_map("materials", material).doc("materials");
  s.choice("integrator", {"symplectic", "verlet"}).default_value("symplectic").doc("scheme");
  s.vector("gravity").unit("m/s^2").default_value({0, 0, -9.81}, {0, -9.81}).doc("g");
  s.integer("steps").min(1).optional().doc("count");
  return s;
}

Diagnostics check(const ParamSet& set, const std::string& text, ParamValues* out = nullptr, int dim = 3) {
  Diagnostics d;
  FakeCatalogue catalogue;
  ValidationContext c{"dam_break.json", ".", dim, &catalogue, &d};
  ParamValues v = validate(set, parse_json(text, "dam_break.json"), "", c);
  if (out) *out = v;
  return d;
}

TEST(Validator, MessagesFromTheDesignBrief) {
  const Diagnostics d = check(scene_like(), R"({
    "materials": { "sand": { "density": 1800,
      "rheology": { "type": "hbp", "yield_stres": 10, "viscosity": 1, "flow_index": -0.5 } } } })");
  EXPECT_EQ(d.format(),
            "error: dam_break.json: /materials/sand/rheology/yield_stres: unknown parameter for rheology 'hbp'\n"
            "       did you mean 'yield_stress'?  known: flow_index, regularisation, viscosity, yield_stress\n"
            "error: dam_break.json: /materials/sand/rheology/yield_stress: missing required parameter (yield stress)\n"
            "error: dam_break.json: /materials/sand/rheology/flow_index: -0.5 is out of range; must be > 0\n");
}

TEST(Validator, TypeChoiceAndModelNameErrorsAreAllCollected) {
  const Diagnostics d = check(scene_like(), R"({
    "materials": { "mud": { "density": "heavy", "rheology": { "type": "bingam" } } },
    "integrator": "leapfrog", "gravity": [0, -9.81], "steps": 2.5 })");
  ASSERT_EQ(d.size(), 5u) << d.format();
  EXPECT_EQ(d.items()[0].pointer, "/materials/mud/density");
  EXPECT_EQ(d.items()[0].message, "expected a number, got the string \"heavy\"");
  EXPECT_EQ(d.items()[1].pointer, "/materials/mud/rheology/type");
  EXPECT_EQ(d.items()[1].message, "unknown rheology 'bingam'");
  EXPECT_EQ(d.items()[1].hint, "did you mean 'bingham'?  known: bingham, hbp");
  EXPECT_EQ(d.items()[2].pointer, "/integrator");
  EXPECT_EQ(d.items()[2].message, "'leapfrog' is not allowed");
  EXPECT_EQ(d.items()[3].pointer, "/gravity");
  EXPECT_EQ(d.items()[3].message, "expected an array of 3 numbers, got an array [0,-9.81]");
  EXPECT_EQ(d.items()[4].pointer, "/steps");
  EXPECT_EQ(d.items()[4].message, "expected an integer, got 2.5");
}

TEST(Validator, DefaultsAreFilledAndVectorsFollowTheDimension) {
  ParamValues v;
  const Diagnostics d = check(scene_like(), R"({"materials": {}})", &v, 2);
  ASSERT_TRUE(d.empty()) << d.format();
  EXPECT_EQ(v.string("integrator"), "symplectic");
  EXPECT_EQ(v.vector("gravity"), (Vec3{0, -9.81, 0}));
  EXPECT_FALSE(v.has("steps"));
}

TEST(Validator, ModelParametersReachTheFactoryTyped) {
  ParamValues v;
  const Diagnostics d = check(scene_like(), R"({"materials": {"sand": {"density": 1800,
      "rheology": {"type": "hbp", "yield_stress": 10, "viscosity": 2}}}})", &v);
  ASSERT_TRUE(d.empty()) << d.format();
  const ParamValues& sand = v.objects("materials").at(0);
  EXPECT_EQ(v.keys("materials").at(0), "sand");
  EXPECT_EQ(sand.model_name("rheology"), "hbp");
  EXPECT_DOUBLE_EQ(sand.model_params("rheology").real("viscosity"), 2.0);
  EXPECT_DOUBLE_EQ(sand.model_params("rheology").real("regularisation"), 100.0);
  EXPECT_EQ(sand.model_params("rheology").pointer("viscosity"), "/materials/sand/rheology/viscosity");
}

TEST(Validator, SemanticChecksRunOnlyOnWellFormedObjects) {
  ParamSet p{"range", "a range"};
  p.real("lo").doc("lower");
  p.real("hi").doc("upper");
  p.check([](const ParamValues& v, Diagnostics& d) {
    if (v.real("hi") <= v.real("lo")) d.error(v, "hi", "must be greater than lo");
  });
  EXPECT_EQ(check(p, R"({"lo": 2, "hi": 1})").format(), "error: dam_break.json: /hi: must be greater than lo\n");
  // With "hi" missing the check does not run (it would read a missing value).
  EXPECT_EQ(check(p, R"({"lo": 2})").size(), 1u);
}

TEST(Validator, OneOfNeedsExactlyOneKnownAlternative) {
  ParamSet box{"box", "box"};
  box.vector("min").doc("lo");
  ParamSet p{"body", "body"};
  p.one_of("shape").alternative("box", box).doc("shape");
  EXPECT_EQ(check(p, R"({"shape": {"bx": {}}})").items().at(0).hint, "did you mean 'box'?  known: box");
  EXPECT_EQ(check(p, R"({"shape": {}})").items().at(0).message,
            "expected an object with exactly one of: box, got an object");
}

TEST(Validator, SyntaxErrorsGiveLineAndColumn) {
  try {
    parse_json("{\n  \"a\": 1,\n  \"b\" 2\n}", "scene.json");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("error: scene.json:3:7: JSON syntax error", 0), 0u) << e.what();
  }
}

// A key given twice in one object is refused with its pointer (the parser
// alone keeps the last value and drops the first silently).
TEST(Validator, DuplicateKeyIsAnErrorNamingItsPointer) {
  auto message = [](const std::string& text) {
    try {
      parse_json(text, "scene.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_EQ(message(R"({"dp": 0.1, "dp": 0.2})").rfind("error: scene.json: /dp: key given twice", 0), 0u);
  const std::string nested = message(R"({"bodies": [{"name": "a"}, {"name": "b", "shape": {"box": {}, "box": {}}}]})");
  EXPECT_EQ(nested.rfind("error: scene.json: /bodies/1/shape/box: key given twice", 0), 0u) << nested;
  const std::string after_array = message(R"({"a": [1, [2, 3], {"x": 1}], "b": {"y": 1, "y": 2}})");
  EXPECT_EQ(after_array.rfind("error: scene.json: /b/y: key given twice", 0), 0u) << after_array;
  // The same key in two objects is fine.
  EXPECT_NO_THROW(parse_json(R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 1}, {"x": 2}]})", "scene.json"));
}

// Deep nesting is refused while parsing (what follows would recurse through
// it), an empty key is an unknown parameter like any other, and a control
// character or a huge value in the input never cuts or floods the report.
TEST(Validator, DeepNestingEmptyKeysAndHostileValuesGiveShortWholeMessages) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  try {
    parse_json(deep, "deep.json");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nested deeper than 64 levels"), std::string::npos);
  }
  ParamSet p{"m", "m"};
  p.real("viscosity").doc("v");
  try {
    params_from_json(p, R"({"": 1, "viscosity": 1})");
    FAIL() << "the empty key was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/: unknown parameter"), std::string::npos) << e.what();
  }
  try {
    params_from_json(p, "{\"vis\\u0000cosity\": 1, \"viscosity\": \"" + std::string(1000000, 'x') + "\"}");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/vis\\u0000cosity: unknown parameter"), std::string::npos) << what.substr(0, 300);
    EXPECT_NE(what.find("/viscosity: expected a number"), std::string::npos) << what.substr(0, 300);
    EXPECT_LT(what.size(), 1000u);
  }
}

// A message laid out over indented lines (a refused plugin's reasons) prints
// as lines; any other control character, a bare line break included, is
// written out, so no text can start a report line of its own.
TEST(Diagnostics, KeepsIndentedLinesAndWritesOutOtherControlCharacters) {
  Diagnostics d;
  d.error("scene.json", "/kernel/type", "refused:\n         - SDK headers differ\nerror: forged\x07", "rebuild it");
  const std::string text = d.format();
  EXPECT_EQ(text,
            "error: scene.json: /kernel/type: refused:\n         - SDK headers differ\\u000aerror: forged\\u0007\n"
            "       rebuild it\n");
}

TEST(Validator, SyntaxErrorKeepsItsReasonWhenTheLastTokenHoldsAColon) {
  try {
    parse_json("{\"a\": \"x: y\" 1}", "scene.json");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("JSON syntax error: syntax error while parsing object"), std::string::npos) << what;
  }
}

TEST(Validator, NumberBeyondADoubleIsAnInputErrorWithLineAndColumn) {
  try {
    parse_json("{\n  \"h\": 1e999\n}", "scene.json");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "error: scene.json:2:8: the number 1e999 is out of range (beyond what a double holds)");
  }
}

TEST(Validator, ParamsFromJsonThrowsEveryProblem) {
  try {
    params_from_json(hbp_like(), R"({"viscosity": 0})");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/yield_stress: missing required parameter"), std::string::npos) << what;
    EXPECT_NE(what.find("/viscosity: 0 is out of range; must be > 0"), std::string::npos) << what;
  }
}

// A file name the system cannot look up (longer than a name may be) is an
// error at its pointer, not a filesystem_error from the validator.
TEST(Validator, FileNameTooLongForTheSystemIsAnErrorAtItsPointer) {
  ParamSet p{"mesh", "a file"};
  p.path("file").doc("file");
  const Diagnostics d = check(p, "{\"file\": \"" + std::string(5000, 'a') + "\"}");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d.items()[0].pointer, "/file");
  EXPECT_NE(d.items()[0].message.find("cannot look up the string \"aaaa"), std::string::npos) << d.format();
  EXPECT_NE(d.items()[0].message.find("File name too long"), std::string::npos) << d.format();
}

// A face index is read as a wide integer first: 4294967297 must not become 1.
TEST(Validator, FaceIndexBeyondAnIntIsRefused) {
  ParamSet p{"polyhedron", "faces"};
  p.index_lists("faces").doc("faces");
  for (const char* bad : {"4294967297", "2147483648", "-1", "18446744073709551615"}) {
    const Diagnostics d = check(p, std::string(R"({"faces": [[0, 1, 2], [0, 1, )") + bad + "]]}");
    ASSERT_EQ(d.size(), 1u) << bad;
    EXPECT_EQ(d.items()[0].pointer, "/faces/1");
    EXPECT_EQ(d.items()[0].message, "expected an array of vertex indices (integers from 0 to 2147483647)");
  }
  ParamValues v;
  EXPECT_TRUE(check(p, R"({"faces": [[0, 1, 2147483647]]})", &v).empty());
  EXPECT_EQ(v.index_lists("faces")[0][2], 2147483647);
}

// An integer beyond int64 is refused (its conversion would be undefined),
// and one beyond 2^53 is read exactly, not through a double.
TEST(Validator, IntegersBeyondInt64AreRefusedAndLargeOnesReadExactly) {
  ParamSet p{"time", "counts"};
  p.integer("steps").min(1).doc("count");
  for (const char* big : {"1e19", "9223372036854775808", "1e308", "-1e19"}) {
    const Diagnostics d = check(p, std::string(R"({"steps": )") + big + "}");
    ASSERT_EQ(d.size(), 1u) << big;
    EXPECT_EQ(d.items()[0].pointer, "/steps");
    EXPECT_NE(d.items()[0].message.find("out of range"), std::string::npos) << d.format();
  }
  ParamValues v;
  EXPECT_TRUE(check(p, R"({"steps": 9007199254740993})", &v).empty());
  EXPECT_EQ(v.integer("steps"), 9007199254740993);
}

}  // namespace
}  // namespace talus
