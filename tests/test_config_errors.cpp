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
        BadInput{"zero spp", {"/render/spp=0"}, "/render/spp"},
        BadInput{"fractional spp", {"/render/spp=1.5"}, "/render/spp"},
        BadInput{"negative resolution", {"/render/resolution=[-8, 8]"}, "/render/resolution/0"},
        BadInput{"unknown sampler", {"/render/sampler=\"sobol\""}, "/render/sampler"},
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
        BadInput{"set with array index out of range", {"/shapes/7/radius=1"}, "/shapes/7/radius"}),
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
