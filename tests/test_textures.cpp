// Textures (scene/textures/*, loader/texture_factory.cpp): checkerboard parity and square
// counts, gradient endpoints and clamping, bilinear image lookups with repeat wrap on a small
// EXR written here, a Radiance .hdr from the asset search path, and the range checks that keep
// every value a texture can produce inside the parameter's range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include "io/exr_io.h"
#include "io/rgb_image_io.h"
#include "loader/texture_factory.h"
#include "support/scene_testing.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

const AssetResolver kNoAssets({});

ShadingContext at(float u, float v) {
    return ShadingContext{Vec2(u, v), Vec3(0.0f)};
}

// The texture of parameter "p" of the object {"p": value} at /m.
TexturePtr<Rgb> rgbTexture(const Json& value, Range range = Range::unit(),
                           const AssetResolver& assets = kNoAssets) {
    const Json object = {{"p", value}};
    const KeyTable keys{"test", "", {key("p").colourTexture(range).byDefault(0.0)}};
    ObjectReader j(object, "/m", keys);
    TexturePtr<Rgb> texture = readRgbTexture(j, "p", assets);
    j.finish();
    return texture;
}
TexturePtr<float> floatTexture(const Json& value, Range range = Range::unit(),
                               const AssetResolver& assets = kNoAssets) {
    const Json object = {{"p", value}};
    const KeyTable keys{"test", "", {key("p").numberTexture(range).byDefault(0.0)}};
    ObjectReader j(object, "/m", keys);
    TexturePtr<float> texture = readFloatTexture(j, "p", assets);
    j.finish();
    return texture;
}

// The pointer of the ConfigError that reading `value` raises, and its message.
std::string errorOf(const Json& value, Range range = Range::unit(),
                    const AssetResolver& assets = kNoAssets, std::string* message = nullptr) {
    try {
        rgbTexture(value, range, assets);
    } catch (const ConfigError& e) {
        if (message) *message = e.what();
        return e.pointer();
    }
    return "<no error>";
}

// --- Constants and checkers ---------------------------------------------------------------------

TEST(Textures, NumbersAndColoursAreConstants) {
    EXPECT_EQ(rgbTexture(0.25)->eval(at(0.3f, 0.9f)), Rgb(0.25f));
    EXPECT_EQ(rgbTexture({0.1, 0.2, 0.3})->eval(at(-4, 7)), Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_NE(constantValue(rgbTexture(0.5)), nullptr);
    EXPECT_EQ(floatTexture(0.75)->eval(at(0, 0)), 0.75f);
}

TEST(CheckerTexture, ParityOfEverySquareCentre) {
    const auto t =
        floatTexture({{"type", "checker"}, {"even", 0.2}, {"odd", 0.7}, {"squares", {3, 5}}});
    EXPECT_EQ(constantValue(t), nullptr);
    for (int i = -3; i < 6; ++i)  // beyond [0, 1) too: the pattern continues
        for (int j = -5; j < 10; ++j) {
            const float expected = (i + j) % 2 == 0 ? 0.2f : 0.7f;
            EXPECT_EQ(t->eval(at((i + 0.5f) / 3, (j + 0.5f) / 5)), expected) << i << ", " << j;
        }
}

// Walking across [0, 1) along u (and v) meets nu (nv) squares: the value changes nu − 1
// times.
TEST(CheckerTexture, SquareCountsAlongEachAxis) {
    for (const auto& [nu, nv] : {std::pair{3, 5}, std::pair{8, 8}, std::pair{1, 2}}) {
        const Json squares = {nu, nv};
        Json description = {{"type", "checker"}, {"even", 0.0}, {"odd", 1.0}};
        if (nu != 8) description["squares"] = squares;  // [8, 8] is the default
        const auto t = floatTexture(description);
        auto changes = [&](bool alongU) {
            int count = 0;
            float previous = t->eval(at(0.0005f, 0.0005f));
            for (int k = 1; k < 1000; ++k) {
                const float s = (k + 0.5f) / 1000;
                const float value = t->eval(alongU ? at(s, 0.0005f) : at(0.0005f, s));
                count += value != previous;
                previous = value;
            }
            return count;
        };
        EXPECT_EQ(changes(true), nu - 1) << nu << "×" << nv;
        EXPECT_EQ(changes(false), nv - 1) << nu << "×" << nv;
    }
}

TEST(CheckerTexture, NestsTextures) {
    const auto t =
        rgbTexture({{"type", "checker"},
                    {"even", {{"type", "gradient"}, {"from", 0.0}, {"to", 1.0}, {"axis", "u"}}},
                    {"odd", {0.1, 0.2, 0.3}},
                    {"squares", {2, 2}}});
    EXPECT_EQ(t->eval(at(0.25f, 0.25f)), Rgb(0.25f));  // even square: the gradient
    EXPECT_EQ(t->eval(at(0.75f, 0.25f)), Rgb(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(t->eval(at(0.75f, 0.75f)), Rgb(0.75f));
}

// --- Gradients --------------------------------------------------------------------------------

TEST(GradientTexture, EndpointsMidpointAndClamping) {
    const auto u = rgbTexture(
        {{"type", "gradient"}, {"from", {0.2, 0.0, 1.0}}, {"to", {0.6, 1.0, 0.0}}, {"axis", "u"}});
    EXPECT_EQ(u->eval(at(0, 0.7f)), Rgb(0.2f, 0.0f, 1.0f));
    EXPECT_EQ(u->eval(at(1, 0.7f)), Rgb(0.6f, 1.0f, 0.0f));
    const Rgb mid = u->eval(at(0.5f, 0.1f));
    EXPECT_NEAR(mid.r, 0.4f, 1e-6f);
    EXPECT_NEAR(mid.g, 0.5f, 1e-6f);
    EXPECT_NEAR(mid.b, 0.5f, 1e-6f);
    EXPECT_EQ(u->eval(at(-3, 0)), Rgb(0.2f, 0.0f, 1.0f));  // clamped, not repeated
    EXPECT_EQ(u->eval(at(7, 0)), Rgb(0.6f, 1.0f, 0.0f));
    // The default axis is v.
    const auto v = floatTexture({{"type", "gradient"}, {"from", 0.1}, {"to", 0.9}});
    EXPECT_FLOAT_EQ(v->eval(at(0.8f, 0)), 0.1f);
    EXPECT_FLOAT_EQ(v->eval(at(0.2f, 1)), 0.9f);
    EXPECT_NEAR(v->eval(at(0.2f, 0.25f)), 0.3f, 1e-6f);
}

// --- Images -------------------------------------------------------------------------------------

// A 3 × 2 EXR: texel (i, j), j = 0 the top row, holds R = i + 3j, G = 10 + i, B = 20 + j, all
// divided by 100 so that every value is a valid albedo.
fs::path writeTestImage() {
    ExrImage image;
    image.width = 3;
    image.height = 2;
    for (const char* c : {"R", "G", "B"})
        image.channels[c].resize(6);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
            image.channels["R"][j * 3 + i] = float(i + 3 * j) / 100;
            image.channels["G"][j * 3 + i] = float(10 + i) / 100;
            image.channels["B"][j * 3 + i] = float(20 + j) / 100;
        }
    const fs::path file = scratchDirectory() / "texture.exr";
    writeExr(file, image);
    return file;
}

Rgb texel(int i, int j) {
    return Rgb(float(i + 3 * j) / 100, float(10 + i) / 100, float(20 + j) / 100);
}

// Texture coordinates of the centre of texel (i, j): row 0 is at the top, v = 0 at the bottom.
ShadingContext centreOf(double i, double j) {
    return at(float((i + 0.5) / 3), float(1 - (j + 0.5) / 2));
}

void expectNear(const Rgb& a, const Rgb& b, const std::string& where) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(a[c], b[c], 1e-6f) << where << ", channel " << c;
}

TEST(ImageTexture, TexelCentresAndBilinearInterpolation) {
    const fs::path file = writeTestImage();
    const AssetResolver assets({file.parent_path()});
    const auto t = rgbTexture({{"type", "image"}, {"file", "texture.exr"}}, Range::unit(), assets);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i)
            expectNear(t->eval(centreOf(i, j)), texel(i, j), "centre " + std::to_string(i));
    // Halfway between neighbours, and the centre of four texels.
    expectNear(t->eval(centreOf(0.5, 0)), (texel(0, 0) + texel(1, 0)) * 0.5f, "horizontal");
    expectNear(t->eval(centreOf(1, 0.5)), (texel(1, 0) + texel(1, 1)) * 0.5f, "vertical");
    expectNear(t->eval(centreOf(1.25, 0.5)),
               (texel(1, 0) * 0.75f + texel(2, 0) * 0.25f) * 0.5f +
                   (texel(1, 1) * 0.75f + texel(2, 1) * 0.25f) * 0.5f,
               "four texels");
}

TEST(ImageTexture, RepeatsAcrossTheEdges) {
    const fs::path file = writeTestImage();
    const AssetResolver assets({file.parent_path()});
    const auto t = rgbTexture({{"type", "image"}, {"file", "texture.exr"}}, Range::unit(), assets);
    // u = 0 lies between the last column and the first; v = 0 (the bottom edge) between the
    // bottom row and the top row.
    expectNear(t->eval(at(0, float(1 - 0.5 / 2))), (texel(2, 0) + texel(0, 0)) * 0.5f, "u = 0");
    expectNear(t->eval(at(float(0.5 / 3), 0)), (texel(0, 1) + texel(0, 0)) * 0.5f, "v = 0");
    for (const float shift : {-2.0f, 1.0f, 5.0f})
        expectNear(t->eval(at(0.3f + shift, 0.6f - shift)), t->eval(at(0.3f, 0.6f)), "repeat");
}

TEST(ImageTexture, FloatParametersTakeLuminanceAndScaleApplies) {
    const fs::path file = writeTestImage();
    const AssetResolver assets({file.parent_path()});
    const auto f = floatTexture({{"type", "image"}, {"file", "texture.exr"}, {"scale", 2}},
                                Range::unit(), assets);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(f->eval(centreOf(i, j)), 2 * texel(i, j).luminance(), 1e-6f);
}

// The image's texels × scale must lie in the parameter's range: checked at load, so a
// material never sees an impossible value.
TEST(ImageTexture, TexelsOutsideTheRangeAreRejectedAtLoad) {
    const fs::path file = writeTestImage();
    const AssetResolver assets({file.parent_path()});
    std::string message;
    // The largest values are B = 0.21 in the bottom row: × 4.9 exceeds 1, × 4.7 does not.
    EXPECT_EQ(errorOf({{"type", "image"}, {"file", "texture.exr"}, {"scale", 4.9}}, Range::unit(),
                      assets, &message),
              "/m/p");
    EXPECT_NE(message.find("texel (0, 1)"), std::string::npos) << message;
    EXPECT_EQ(errorOf({{"type", "image"}, {"file", "texture.exr"}, {"scale", 4.7}}, Range::unit(),
                      assets),
              "<no error>");
    // An open range: texel (0, 0) has R = 0, not > 0.
    EXPECT_EQ(errorOf({{"type", "image"}, {"file", "texture.exr"}}, Range::positive(), assets),
              "/m/p");
}

TEST(ImageTexture, MissingFileNamesTheFileAndTheSearchPath) {
    const AssetResolver assets({"/nonexistent/first", "/nonexistent/second"});
    std::string message;
    EXPECT_EQ(
        errorOf({{"type", "image"}, {"file", "maps/nothing.exr"}}, Range::unit(), assets, &message),
        "/m/p/file");
    EXPECT_NE(message.find("maps/nothing.exr"), std::string::npos) << message;
    EXPECT_NE(message.find("/nonexistent/first, /nonexistent/second"), std::string::npos)
        << message;
}

TEST(ImageTexture, UnreadableAndUnsupportedFilesAreErrors) {
    const fs::path dir = scratchDirectory();
    std::ofstream(dir / "broken.hdr") << "not a Radiance file";
    std::ofstream(dir / "picture.png") << "png";
    const AssetResolver assets({dir});
    std::string message;
    EXPECT_EQ(errorOf({{"type", "image"}, {"file", "broken.hdr"}}, Range::unit(), assets, &message),
              "/m/p/file");
    EXPECT_NE(message.find("broken.hdr"), std::string::npos) << message;
    EXPECT_EQ(
        errorOf({{"type", "image"}, {"file", "picture.png"}}, Range::unit(), assets, &message),
        "/m/p/file");
    EXPECT_NE(message.find(".exr or .hdr"), std::string::npos) << message;
}

// A Radiance file from the asset search path, against the statistics verified in the
// assets' README (Rec. 709 luminance of the linear values: max 13.77, mean 1.782).
TEST(RadianceImage, ReadsTheUffiziProbeWithItsVerifiedStatistics) {
    const AssetResolver assets = AssetResolver::standard(TEST_SCENES_DIR);
    const auto path = assets.resolve("envmaps/extra/uffizi_ict_latlong_256x128.hdr");
    if (!path) {
        const char* require = std::getenv("REQUIRE_ASSETS");
        if (require && std::string(require) == "1")
            FAIL() << "REQUIRE_ASSETS=1 but the map is not on " << assets.describe();
        GTEST_SKIP() << "no envmaps/extra/uffizi_ict_latlong_256x128.hdr on " << assets.describe();
    }
    const RgbImage image = readRgbImage(*path);
    ASSERT_EQ(image.width, 256);
    ASSERT_EQ(image.height, 128);
    double maxY = 0, sumY = 0;
    for (const Rgb& p : image.pixels) {
        ASSERT_TRUE(p.isFinite());
        maxY = std::max(maxY, double(p.luminance()));
        sumY += p.luminance();
    }
    EXPECT_NEAR(maxY, 13.77, 0.005);
    EXPECT_NEAR(sumY / image.pixels.size(), 1.782, 0.0005);
    // As a texture (no range to respect here beyond finiteness): the top-left texel's centre.
    const auto t = rgbTexture({{"type", "image"}, {"file", path->string()}}, Range::any(), assets);
    expectNear(t->eval(at(0.5f / 256, 1 - 0.5f / 128)), image.pixels[0], "top-left texel");
}

// --- Range checks of constants and nested textures ---------------------------------------------

TEST(TextureRanges, EveryConstantIsCheckedWhereItIsWritten) {
    EXPECT_EQ(errorOf(1.5), "/m/p");
    EXPECT_EQ(errorOf({{"type", "gradient"}, {"from", 0.0}, {"to", 1.5}}), "/m/p/to");
    EXPECT_EQ(errorOf({{"type", "gradient"}, {"from", -0.5}, {"to", 1}}), "/m/p/from");
    EXPECT_EQ(errorOf({{"type", "checker"}, {"even", 0.5}, {"odd", {0.5, 2, 0.5}}}), "/m/p/odd/1");
    EXPECT_EQ(errorOf({{"type", "checker"},
                       {"even", {{"type", "gradient"}, {"from", 0}, {"to", 3}}},
                       {"odd", 0.5}}),
              "/m/p/even/to");
    // The open range of a roughness: 0 is impossible even as a gradient endpoint.
    EXPECT_EQ(errorOf({{"type", "gradient"}, {"from", 0}, {"to", 1}}, Range{0, 1, true, false}),
              "/m/p/from");
}

TEST(TextureRanges, MalformedTextureObjects) {
    EXPECT_EQ(errorOf({{"type", "noise"}}), "/m/p/type");
    EXPECT_EQ(errorOf({{"from", 0}}), "/m/p/type");
    EXPECT_EQ(errorOf({{"type", "checker"}, {"even", 0.5}}), "/m/p/odd");  // required
    EXPECT_EQ(errorOf({{"type", "checker"}, {"even", 0.5}, {"odd", 0.5}, {"squares", {2.5, 2}}}),
              "/m/p/squares");
    EXPECT_EQ(errorOf({{"type", "checker"}, {"even", 0.5}, {"odd", 0.5}, {"squares", {0, 2}}}),
              "/m/p/squares/0");
    EXPECT_EQ(errorOf({{"type", "gradient"}, {"from", 0}, {"to", 1}, {"axis", "w"}}), "/m/p/axis");
    EXPECT_EQ(errorOf({{"type", "gradient"}, {"from", 0}, {"to", 1}, {"colour", 1}}),
              "/m/p/colour");  // unknown keys are errors
}

// A sphere's uv poles lie on its own z axis, which its transform's rotation turns: rotated by
// −90° about x, the pole faces +y, so a ray down onto the top hits v = 0, and on the equator the
// tangent (the u axis of anisotropic materials) runs along the parallel, perpendicular to y.
// (The camera is at the origin, so that rendering space is the file's.)
TEST(SphereCoordinates, FollowTheSphereRotation) {
    const LoadedScene scene = loadSceneText(R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1]},
        "shapes": [{"type": "sphere", "radius": 1, "material": {"type": "lambert"},
                    "transform": {"rotate": {"axis": [1, 0, 0], "angle": -90},
                                  "translate": [0, 0, 0]}}],
        "lights": [{"type": "point", "position": [0, 3, 0], "intensity": 1}]})");
    SurfaceHit top;
    ASSERT_TRUE(scene.scene->intersect(Ray{Vec3(0.001f, 5, 0), Vec3(0, -1, 0), 100, 0}, &top));
    EXPECT_NEAR(top.uv.y, 0.0f, 1e-3f);
    SurfaceHit side;
    ASSERT_TRUE(scene.scene->intersect(Ray{Vec3(0, 0, 5), Vec3(0, 0, -1), 100, 0}, &side));
    EXPECT_NEAR(side.uv.y, 0.5f, 1e-3f);
    EXPECT_NEAR(std::abs(dot(normalize(side.tangent), Vec3(1, 0, 0))), 1.0f, 1e-4f);
}

}  // namespace
}  // namespace rr::test
