// Every class of bad input is a ConfigError naming the JSON pointer of the offending value.
// (test_cli checks the binary's side: exit status 2, one message, nothing written.)
#include <gtest/gtest.h>

#include "support/scene_testing.h"

namespace rr::test {
namespace {

// A valid minimal scene; each case breaks one thing with a --set style override.
const char* kValid = R"({
  "render": {"resolution": [8, 8], "spp": 1},
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
  "materials": {"white": {"type": "lambert", "albedo": 0.5},
                "glass": {"type": "dielectric", "ior": 1.5}},
  "shapes": [
    {"type": "quad", "corner": [-1, 1, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2],
     "emission": {"radiance": 4}},
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "white"}
  ],
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 1}]
})";

std::string errorPointer(const std::string& text, const std::vector<std::string>& overrides) {
    try {
        Json doc = parseSceneText(text, "test");
        for (const auto& o : overrides)
            applyOverride(doc, o);
        loadScene(doc, AssetResolver({}));
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(e.pointer().empty() ? "/" : e.pointer()),
                  std::string::npos)
            << "the message must name the pointer: " << e.what();
        return e.pointer();
    }
    return "<no error>";
}

TEST(ConfigErrors, TheValidSceneLoads) {
    EXPECT_EQ(errorPointer(kValid, {}), "<no error>");
}

struct BadInput {
    const char* what;
    std::vector<std::string> overrides;
    const char* pointer;
};

void PrintTo(const BadInput& b, std::ostream* os) {
    *os << b.what;
}

// A regular polygon of n vertices in the plane z = 0, as a shape override that emits.
std::string regularPolygon(int n) {
    std::string vertices;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * M_PI * i / n;
        vertices += (i ? ",[" : "[") + std::to_string(std::cos(a)) + "," +
                    std::to_string(std::sin(a)) + ",0]";
    }
    return R"(/shapes/0={"type":"polygon","vertices":[)" + vertices +
           R"(],"emission":{"radiance":1}})";
}

class ConfigErrorCases : public ::testing::TestWithParam<BadInput> {};

TEST_P(ConfigErrorCases, NamesThePointer) {
    EXPECT_EQ(errorPointer(kValid, GetParam().overrides), GetParam().pointer) << GetParam().what;
}

INSTANTIATE_TEST_SUITE_P(
    All, ConfigErrorCases,
    ::testing::Values(
        BadInput{"unknown top-level key", {"/rendr={}"}, "/rendr"},
        BadInput{"unknown camera key", {"/camera/fovv=30"}, "/camera/fovv"},
        BadInput{"unknown shape key", {"/shapes/1/radiu=1"}, "/shapes/1/radiu"},
        BadInput{"unknown material key",
                 {"/materials/white/roughness=0.1"},
                 "/materials/white/roughness"},
        BadInput{"wrong type", {"/camera/fov=\"wide\""}, "/camera/fov"},
        BadInput{"wrong type in array", {"/camera/position=[0, \"a\", 3]"}, "/camera/position/1"},
        BadInput{"wrong array length", {"/camera/position=[0, 3]"}, "/camera/position"},
        BadInput{"negative radius", {"/shapes/1/radius=-1"}, "/shapes/1/radius"},
        BadInput{"zero radius", {"/shapes/1/radius=0"}, "/shapes/1/radius"},
        BadInput{"zero-area light", {"/shapes/0/edge_v=[0, 0, 0]"}, "/shapes/0/edge_v"},
        BadInput{"parallel quad edges", {"/shapes/0/edge_v=[4, 0, 0]"}, "/shapes/0/edge_v"},
        BadInput{
            "negative radiance", {"/shapes/0/emission/radiance=-1"}, "/shapes/0/emission/radiance"},
        BadInput{"albedo above one",
                 {"/materials/white/albedo=[0.5, 1.5, 0.5]"},
                 "/materials/white/albedo/1"},
        BadInput{"unknown TAIS map",
                 {R"(/integrator={"type":"tais","maps":["lens","colour"]})"},
                 "/integrator/maps/1"},
        BadInput{"TAIS map the scene has no decision for (a static pinhole scene)",
                 {R"(/integrator={"type":"tais","maps":["light_selection","time"]})"},
                 "/integrator/maps/1"},
        BadInput{"TAIS map listed twice",
                 {R"(/integrator={"type":"tais","maps":["bifurcation","bifurcation"]})"},
                 "/integrator/maps/1"},
        BadInput{"TAIS maps neither auto nor a list",
                 {R"(/integrator={"type":"tais","maps":"all"})"},
                 "/integrator/maps"},
        BadInput{
            "TAIS alpha of 1", {R"(/integrator={"type":"tais","alpha":1})"}, "/integrator/alpha"},
        BadInput{"TAIS 2-D map of one cell",
                 {R"(/integrator={"type":"tais","lens_size":1})"},
                 "/integrator/lens_size"},
        BadInput{
            "unknown TAIS key", {R"(/integrator={"type":"tais","band":4})"}, "/integrator/band"},
        BadInput{"index of refraction zero", {"/materials/glass/ior=0"}, "/materials/glass/ior"},
        BadInput{
            "unknown material type", {"/materials/white/type=\"velvet\""}, "/materials/white/type"},
        BadInput{"unknown material name", {"/shapes/1/material=\"chalk\""}, "/shapes/1/material"},
        BadInput{"unknown shape type", {"/shapes/1/type=\"torus\""}, "/shapes/1/type"},
        BadInput{"unknown light type", {"/lights/0/type=\"laser\""}, "/lights/0/type"},
        BadInput{"unknown integrator", {"/integrator={\"type\":\"bdpt\"}"}, "/integrator/type"},
        BadInput{"integrator parameter of another type",
                 {"/integrator={\"type\":\"path\",\"strategy\":\"mis\"}"},
                 "/integrator/strategy"},
        BadInput{"strategy and estimator both given",
                 {R"(/integrator={"type":"direct","strategy":"mis","estimator":{"type":"light"}})"},
                 "/integrator/strategy"},
        BadInput{"ris with no candidates",
                 {R"(/integrator={"type":"ris","mode":"fixed","candidates":0})"},
                 "/integrator/candidates"},
        BadInput{
            "ris robust without a budget", {R"(/integrator={"type":"ris"})"}, "/integrator/budget"},
        BadInput{"ris fixed with a budget",
                 {R"(/integrator={"type":"ris","mode":"fixed","budget":20})"},
                 "/integrator/budget"},
        BadInput{"ris robust with a fixed M",
                 {R"(/integrator={"type":"ris","budget":20,"candidates":4})"},
                 "/integrator/candidates"},
        BadInput{
            "ris costs with an unknown key",
            {R"(/integrator={"type":"ris","budget":20,"costs":{"t_x_ns":1,"t_y_ns":2,"t_z_ns":3}})"},
            "/integrator/costs/t_z_ns"},
        BadInput{"ris estimator with an unknown source",
                 {R"(/integrator={"type":"path_mis","estimator":{"type":"ris","source":"sky"}})"},
                 "/integrator/estimator/source"},
        BadInput{"ris mixture source with an area light",
                 {R"(/integrator={"type":"ris","mode":"fixed","source":"mixture"})"},
                 "/integrator/source"},
        BadInput{
            "ris mixture estimator with an area light",
            {R"(/integrator={"type":"path_mis","estimator":{"type":"ris","source":"mixture"}})"},
            "/integrator/estimator/source"},
        BadInput{"unknown estimator",
                 {R"(/integrator={"type":"path_mis","estimator":{"type":"magic"}})"},
                 "/integrator/estimator/type"},
        BadInput{"unknown estimator key",
                 {R"(/integrator={"type":"direct","estimator":{"type":"bsdf","light_samples":2}})"},
                 "/integrator/estimator/light_samples"},
        BadInput{"estimator of an integrator without one",
                 {R"(/integrator={"type":"path","estimator":{"type":"mis"}})"},
                 "/integrator/estimator"},
        BadInput{"zero spp", {"/render/spp=0"}, "/render/spp"},
        BadInput{"fractional spp", {"/render/spp=1.5"}, "/render/spp"},
        BadInput{"negative resolution", {"/render/resolution=[-8, 8]"}, "/render/resolution/0"},
        BadInput{"unknown sampler", {"/render/sampler=\"sobol\""}, "/render/sampler"},
        BadInput{
            "zero Russian roulette survival", {"/render/rr_survival=0"}, "/render/rr_survival"},
        BadInput{"Russian roulette survival above one",
                 {"/render/rr_survival=1.5"},
                 "/render/rr_survival"},
        BadInput{
            "zero Russian roulette threshold", {"/render/rr_threshold=0"}, "/render/rr_threshold"},
        BadInput{"Russian roulette threshold beside a fixed survival",
                 {"/render/rr_survival=0.5", "/render/rr_threshold=0.5"},
                 "/render/rr_threshold"},
        BadInput{"fov out of range", {"/camera/fov=180"}, "/camera/fov"},
        BadInput{"camera looks at itself", {"/camera/look_at=[0, 0, 3]"}, "/camera/look_at"},
        BadInput{"thin lens without aperture",
                 {"/camera/type=\"thin_lens\""},
                 "/camera/aperture_radius"},
        BadInput{"shutter reversed", {"/camera/shutter=[0.8, 0.2]"}, "/camera/shutter"},
        BadInput{"missing mesh file",
                 {"/shapes/1={\"type\":\"mesh\",\"file\":\"meshes/"
                  "nothing.ply\",\"material\":\"white\"}"},
                 "/shapes/1/file"},
        BadInput{"sphere with non-uniform scale",
                 {"/shapes/1/transform={\"scale\":[1,2,1]}"},
                 "/shapes/1/transform"},
        BadInput{"singular transform",
                 {"/shapes/0/transform={\"scale\":[1,0,1]}"},
                 "/shapes/0/transform"},
        BadInput{"shape without material", {"/shapes/1/material=null"}, "/shapes/1/material"},
        BadInput{"missing camera", {"/camera/position=null"}, "/camera/position"},
        BadInput{"set with missing parent", {"/camera/lens/radius=1"}, "/camera/lens/radius"},
        BadInput{"set with array index out of range", {"/shapes/7/radius=1"}, "/shapes/7/radius"},
        BadInput{"set with array index beyond 64 bits",
                 {"/shapes/99999999999999999999999={}"},
                 "/shapes/99999999999999999999999"},
        BadInput{"set through array index beyond 64 bits",
                 {"/shapes/99999999999999999999999/radius=1"},
                 "/shapes/99999999999999999999999/radius"},
        BadInput{
            "huge number", {"/shapes/0/emission/radiance=1e39"}, "/shapes/0/emission/radiance"},
        BadInput{"tiny non-zero number",
                 {"/shapes/0/emission/radiance=1e-50"},
                 "/shapes/0/emission/radiance"},
        BadInput{"huge array element", {"/camera/position=[0, 1e11, 3]"}, "/camera/position/1"},
        BadInput{"tiny array element",
                 {"/shapes/0/emission/radiance=[1, 1e-31, 1]"},
                 "/shapes/0/emission/radiance/1"},
        BadInput{"huge aperture",
                 {"/camera/type=\"thin_lens\"", "/camera/aperture_radius=1e39",
                  "/camera/focus_distance=3"},
                 "/camera/aperture_radius"},
        BadInput{"projective matrix",
                 {"/shapes/1/transform={\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0.5,1]}"},
                 "/shapes/1/transform/matrix/14"},
        BadInput{"matrix with bottom-right not one",
                 {"/shapes/1/transform={\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,2]}"},
                 "/shapes/1/transform/matrix/15"},
        BadInput{"singular matrix",
                 {"/shapes/0/transform={\"matrix\":[1,0,0,0, 0,0,0,0, 0,0,1,0, 0,0,0,1]}"},
                 "/shapes/0/transform"},
        BadInput{"nearly singular shear",
                 {"/shapes/0/transform={\"matrix\":[1,1,0,0, 0,1e-7,0,0, 0,0,1,0, 0,0,0,1]}"},
                 "/shapes/0/transform"},
        BadInput{"duplicate key in a --set value",
                 {"/integrator={\"type\":\"path\",\"type\":\"direct\"}"},
                 "/integrator/type"},
        BadInput{"zero up", {"/camera/up=[0, 0, 0]"}, "/camera/up"},
        BadInput{"up parallel to the view", {"/camera/up=[0, 0, 1e-5]"}, "/camera/up"},
        BadInput{"too many pixels", {"/render/resolution=[16384, 16384]"}, "/render/resolution"},
        BadInput{"spp times light_samples beyond 2^24",
                 {"/render/spp=32768", "/integrator={\"type\":\"direct\",\"light_samples\":1024}"},
                 "/render/spp"},
        BadInput{"polygon source sampling unknown",
                 {R"(/shapes/0={"type":"polygon","vertices":[[0,0,0],[1,0,0],[0,1,0]],)"
                  R"("sampling":"cone","emission":{"radiance":1}})"},
                 "/shapes/0/sampling"},
        BadInput{"polygon with two vertices",
                 {R"(/shapes/0={"type":"polygon","vertices":[[0,0,0],[1,0,0]],)"
                  R"("emission":{"radiance":1}})"},
                 "/shapes/0/vertices"},
        BadInput{"polygon with more than 64 vertices", {regularPolygon(65)}, "/shapes/0/vertices"},
        BadInput{"polygon vertex not a point",
                 {R"(/shapes/0={"type":"polygon","vertices":[[0,0,0],[1,0],[0,1,0]],)"
                  R"("emission":{"radiance":1}})"},
                 "/shapes/0/vertices/1"},
        BadInput{"polygon off its plane",
                 {R"(/shapes/0={"type":"polygon","vertices":[[0,0,0],[2,0,0],[2.5,1,0.05],)"
                  R"([1,2,0],[-0.5,1,0]],"emission":{"radiance":1}})"},
                 "/shapes/0/vertices/2"},
        BadInput{"non-convex polygon",
                 {R"(/shapes/0={"type":"polygon","vertices":[[0,0,0],[2,0,0],[1,0.5,0],[2,)"
                  R"(2,0],[0,2,0]],"emission":{"radiance":1}})"},
                 "/shapes/0/vertices/2"},
        BadInput{"self-intersecting polygon (pentagram)",
                 {R"(/shapes/0={"type":"polygon","vertices":[[1,0,0],[-0.809,0.588,0],)"
                  R"([0.309,-0.951,0],[0.309,0.951,0],[-0.809,-0.588,0]],)"
                  R"("emission":{"radiance":1}})"},
                 "/shapes/0/vertices"},
        BadInput{"polygon of collinear points",
                 {R"(/shapes/0={"type":"polygon","vertices":[[0,0,0],[1,1,1],[2,2,2]],)"
                  R"("emission":{"radiance":1}})"},
                 "/shapes/0/vertices"},
        BadInput{"polygon with a repeated vertex",
                 {R"(/shapes/0={"type":"polygon","vertices":[[0,0,0],[1,0,0],[1,0,0],[0,1,)"
                  R"(0]],"emission":{"radiance":1}})"},
                 "/shapes/0/vertices/2"},
        BadInput{"spot falloff beyond the cone",
                 {R"(/lights/0={"type":"spot","position":[0,2,0],"look_at":[0,0,0],)"
                  R"("intensity":1,"cone_angle":20,"falloff_start":30})"},
                 "/lights/0/falloff_start"},
        BadInput{"spot cone of zero",
                 {R"(/lights/0={"type":"spot","position":[0,2,0],"look_at":[0,0,0],)"
                  R"("intensity":1,"cone_angle":0})"},
                 "/lights/0/cone_angle"},
        BadInput{"spot cone beyond 90 degrees",
                 {R"(/lights/0={"type":"spot","position":[0,2,0],"look_at":[0,0,0],)"
                  R"("intensity":1,"cone_angle":91})"},
                 "/lights/0/cone_angle"},
        BadInput{"spot looking at itself",
                 {R"(/lights/0={"type":"spot","position":[0,2,0],"look_at":[0,2,0],)"
                  R"("intensity":1,"cone_angle":30})"},
                 "/lights/0/look_at"},
        BadInput{"environment with radiance and file",
                 {R"(/lights/0={"type":"environment","radiance":1,"file":"envmaps/x.hdr",)"
                  R"("layout":"probe"})"},
                 "/lights/0/radiance"},
        BadInput{"environment of unknown sampling",
                 {R"(/lights/0={"type":"environment","radiance":1,"sampling":"fancy"})"},
                 "/lights/0/sampling"},
        BadInput{"environment map without layout",
                 {R"(/lights/0={"type":"environment","file":"envmaps/x.hdr"})"},
                 "/lights/0/layout"},
        BadInput{"environment map of unknown layout",
                 {R"(/lights/0={"type":"environment","file":"envmaps/x.hdr","layout":"cube"})"},
                 "/lights/0/layout"},
        BadInput{"environment map scaled",
                 {R"(/lights/0={"type":"environment","file":"envmaps/x.hdr",)"
                  R"("layout":"probe","transform":{"scale":2}})"},
                 "/lights/0/transform"},
        BadInput{"environment map translated",
                 {R"(/lights/0={"type":"environment","file":"envmaps/x.hdr",)"
                  R"("layout":"probe","transform":{"translate":[0,1,0]}})"},
                 "/lights/0/transform"},
        BadInput{"environment map mirrored",
                 {R"(/lights/0={"type":"environment","file":"envmaps/x.hdr",)"
                  R"("layout":"probe","transform":{"matrix":[-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,)"
                  R"(0,0,1]}})"},
                 "/lights/0/transform"},
        BadInput{
            "environment map missing",
            {R"(/lights/0={"type":"environment","file":"envmaps/nothing.hdr","layout":"probe"})"},
            "/lights/0/file"},
        BadInput{"environment map with negative scale",
                 {R"(/lights/0={"type":"environment","file":"envmaps/x.hdr",)"
                  R"("layout":"probe","scale":-1})"},
                 "/lights/0/scale"},
        BadInput{"spp times bsdf_samples beyond 2^24",
                 {"/render/spp=65536", "/integrator={\"type\":\"direct\",\"bsdf_samples\":512}"},
                 "/render/spp"}),
    [](const ::testing::TestParamInfo<BadInput>& param) {
        std::string name = param.param.what;
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

TEST(ConfigErrors, MalformedJsonNamesLineAndColumn) {
    try {
        parseSceneText("{\n  \"camera\": {\n    \"fov\": 40,,\n  }\n}", "bad.json");
        FAIL() << "expected a ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
    }
}

// Values near the limits that must still load: the magnitude bound applies to real numbers
// only, and a uniformly tiny scale is not singular.
TEST(ConfigErrors, ValuesNearTheLimitsLoad) {
    const std::vector<std::vector<std::string>> valid = {
        {"/shapes/1/transform={\"scale\":0.0001}"},
        {"/shapes/0/transform={\"scale\":0.0001}"},
        {"/shapes/1/transform={\"matrix\":[1e-4,0,0,0, 0,1e-4,0,0, 0,0,1e-4,0, 0,0,0,1]}"},
        {"/shapes/1/transform={\"scale\":1e4}"},
        {"/camera/up=[0, 1e-5, 0]"},
        {"/camera/up=[0, 1e-10, 0]"},
        {"/shapes/0/emission/radiance=1e10"},
        {"/shapes/0/emission/radiance=[1e-10, 0, 1]"},
        {"/shapes/1/transform={\"matrix\": [1, 1e-17, 0, 0, -2e-17, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, "
         "1]}"},
        {"/render/seed=4294967295"},
        {"/render/spp=16777216"},
        {"/render/resolution=[8192, 8192]"},
        {"/render/spp=16384", "/integrator={\"type\":\"direct\",\"light_samples\":1024}"},
    };
    for (const auto& overrides : valid)
        EXPECT_EQ(errorPointer(kValid, overrides), "<no error>") << overrides.back();
}

// `text` with the first occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

TEST(ConfigErrors, DuplicateKeysNameThePointer) {
    // Top level.
    EXPECT_EQ(errorPointer(replaced(kValid, "\"render\"", "\"render\": {}, \"render\""), {}),
              "/render");
    // Nested in an array element, after arrays and objects that must not disturb the index.
    EXPECT_EQ(
        errorPointer(replaced(kValid, "\"radius\": 0.5", "\"radius\": 0.35, \"radius\": 0.1"), {}),
        "/shapes/1/radius");
    EXPECT_EQ(
        errorPointer(replaced(kValid, "\"radiance\": 4", "\"radiance\": 4, \"radiance\": 4"), {}),
        "/shapes/0/emission/radiance");
    EXPECT_EQ(errorPointer(
                  replaced(kValid, "\"intensity\": 1", "\"intensity\": 1, \"intensity\": 2"), {}),
              "/lights/0/intensity");
    // Keys are escaped as JSON pointer tokens.
    EXPECT_EQ(errorPointer(R"({"a/b~": [1, [2, 3], {"x": 1}, {"x": 1, "x": 2}]})", {}),
              "/a~1b~0/3/x");
    // The same key in different objects is fine, and comments are still allowed.
    EXPECT_EQ(errorPointer(replaced(kValid, "\"render\"", "// a comment\n  \"render\""), {}),
              "<no error>");
    try {
        parseSceneText(R"({"a": 1, /* c */ "b": {"a": 2, "b": 3}, "a": 4})", "dup.json");
        FAIL() << "expected a ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.pointer(), "/a");
        EXPECT_NE(std::string(e.what()).find("duplicate key"), std::string::npos) << e.what();
    }
}

TEST(ConfigErrors, MagnitudeMessageSaysTheBound) {
    try {
        Json doc = parseSceneText(kValid, "test");
        applyOverride(doc, "/shapes/0/emission/radiance=1e-50");
        loadScene(doc, AssetResolver({}));
        FAIL() << "expected a ConfigError";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("between 1e-30 and 1e10 (or 0)"), std::string::npos)
            << e.what();
    }
}

TEST(ConfigErrors, SceneWithoutLightsIsRejected) {
    Json doc = parseSceneText(kValid, "test");
    doc["shapes"].erase(0);
    doc.erase("lights");
    EXPECT_THROW(loadScene(doc, AssetResolver({})), ConfigError);
}

TEST(ConfigErrors, MissingMeshMessageSaysWhereToPutIt) {
    Json doc = parseSceneText(kValid, "test");
    doc["shapes"][1] = {{"type", "mesh"}, {"file", "meshes/nothing.ply"}, {"material", "white"}};
    try {
        loadScene(doc, AssetResolver({"/nonexistent/dir"}));
        FAIL();
    } catch (const ConfigError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("meshes/nothing.ply"), std::string::npos) << m;
        EXPECT_NE(m.find("/nonexistent/dir"), std::string::npos) << m;
        EXPECT_NE(m.find("make assets"), std::string::npos) << m;
    }
}

}  // namespace
}  // namespace rr::test
