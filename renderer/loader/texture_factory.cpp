#include "loader/texture_factory.h"

#include <cmath>
#include <optional>

#include "config/type_table.h"
#include "loader/asset_files.h"
#include "scene/textures/checker.h"
#include "scene/textures/gradient.h"
#include "scene/textures/image.h"

namespace rr {

namespace {

// A texture's value keys take the range of the key that holds the texture.
KeySpec valueKey(const char* name, const char* meaning) {
    return key(name)
        .custom("a constant (number, or colour) or a texture, in the parameter's range",
                {{"anyOf",
                  {{{"type", "number"}},
                   {{"type", "array"},
                    {"items", {{"type", "number"}}},
                    {"minItems", 3},
                    {"maxItems", 3}},
                   {{"$ref", "#/$defs/texture"}}}}})
        .means(meaning);
}

const KeyTable kCheckerKeys{
    "texture/checker",
    "`even` where ⌊u·nu⌋ + ⌊v·nv⌋ is even, `odd` elsewhere; the pattern continues outside [0, 1)²",
    {valueKey("even", "the even squares' value"), valueKey("odd", "the odd squares' value"),
     squaresKey()}};

const KeyTable kGradientKeys{
    "texture/gradient",
    "from + (to − from)·t, with t the coordinate clamped to [0, 1]",
    {valueKey("from", "the value at t = 0 (a constant)"),
     valueKey("to", "the value at t = 1 (a constant)"),
     key("axis").choice({"u", "v"}).byDefault("v").means("the coordinate t")}};

const KeyTable kImageKeys{
    "texture/image",
    "scale × the bilinear interpolation between texel centres, repeating in u and v (the file's "
    "top row at v = 1); a number key takes the texels' Rec. 709 luminance",
    {key("file").string().means(
         "an OpenEXR (channels R, G, B, or Y) or Radiance .hdr file on the asset search path"),
     key("scale").number().byDefault(1.0).means("multiplies every texel")}};

// What differs between float and colour parameters: how a constant is read, how an image
// texel becomes a value (a float parameter takes the texel's Rec. 709 luminance), and the
// range check of a computed value.
template <class T>
struct ValueTraits;

template <>
struct ValueTraits<float> {
    static float read(ObjectReader& j, const std::string& key, std::optional<float> fallback,
                      Range range) {
        return fallback ? j.getFloat(key, *fallback, range) : j.getFloat(key, range);
    }
    static float fromTexel(const Rgb& texel) { return texel.luminance(); }
    static bool inRange(float v, const Range& range) {
        return std::isfinite(v) && range.contains(v);
    }
    static std::string describe(float v) { return std::to_string(v); }
};

template <>
struct ValueTraits<Rgb> {
    static Rgb read(ObjectReader& j, const std::string& key, std::optional<Rgb> fallback,
                    Range range) {
        return fallback ? j.getRgb(key, *fallback, range) : j.getRgb(key, range);
    }
    static Rgb fromTexel(const Rgb& texel) { return texel; }
    static bool inRange(const Rgb& v, const Range& range) {
        for (int c = 0; c < 3; ++c)
            if (!ValueTraits<float>::inRange(v[c], range)) return false;
        return true;
    }
    static std::string describe(const Rgb& v) {
        return "[" + std::to_string(v.r) + ", " + std::to_string(v.g) + ", " + std::to_string(v.b) +
               "]";
    }
};

template <class T>
TexturePtr<T> readTexture(ObjectReader& json, const std::string& key, std::optional<T> fallback,
                          Range range, const AssetResolver& assets);

template <class T>
std::unique_ptr<Texture<T>> makeChecker(ObjectReader& j, Range range, const AssetResolver& assets) {
    TexturePtr<T> even = readTexture<T>(j, "even", std::nullopt, range, assets);
    TexturePtr<T> odd = readTexture<T>(j, "odd", std::nullopt, range, assets);
    return std::make_unique<CheckerTexture<T>>(std::move(even), std::move(odd),
                                               readCheckerboard(j));
}

template <class T>
std::unique_ptr<Texture<T>> makeGradient(ObjectReader& j, Range range, const AssetResolver&) {
    const T from = ValueTraits<T>::read(j, "from", std::nullopt, range);
    const T to = ValueTraits<T>::read(j, "to", std::nullopt, range);
    const auto axis =
        j.choice("axis") == "u" ? GradientTexture<T>::Axis::U : GradientTexture<T>::Axis::V;
    return std::make_unique<GradientTexture<T>>(from, to, axis);
}

template <class T>
std::unique_ptr<Texture<T>> makeImage(ObjectReader& j, Range range, const AssetResolver& assets) {
    const RgbImage image = readImageAsset(j, "file", assets, "image");
    const float scale = j.real("scale");
    if (image.width < 1 || image.height < 1) j.fail("file", "the image is empty");
    std::vector<T> texels;
    texels.reserve(image.pixels.size());
    for (const Rgb& pixel : image.pixels) {
        const T value = ValueTraits<T>::fromTexel(pixel * scale);
        if (!ValueTraits<T>::inRange(value, range)) {
            const size_t i = texels.size();
            throw ConfigError(
                j.pointer(), "texel (" + std::to_string(i % image.width) + ", " +
                                 std::to_string(i / image.width) + ") of \"" + j.getString("file") +
                                 "\" × scale = " + ValueTraits<T>::describe(value) +
                                 " is outside the parameter's range (" + range.describe() + ")");
        }
        texels.push_back(value);
    }
    return std::make_unique<ImageTexture<T>>(image.width, image.height, std::move(texels));
}

template <class T>
const TypeTable<Texture<T>, Range, const AssetResolver&>& textureTypes() {
    static const TypeTable<Texture<T>, Range, const AssetResolver&> table{
        {"checker", {makeChecker<T>, &kCheckerKeys}},
        {"gradient", {makeGradient<T>, &kGradientKeys}},
        {"image", {makeImage<T>, &kImageKeys}},
    };
    return table;
}

template <class T>
TexturePtr<T> makeTexture(ObjectReader& j, Range range, const AssetResolver& assets) {
    return buildByType(j, "texture", textureTypes<T>(), range, assets);
}

// A texture object, or a constant (required when there is no fallback).
template <class T>
TexturePtr<T> readTexture(ObjectReader& json, const std::string& key, std::optional<T> fallback,
                          Range range, const AssetResolver& assets) {
    if (const Json* value = json.rawOptional(key); value && value->is_object()) {
        ObjectReader texture(*value, json.pointerTo(key));
        return makeTexture<T>(texture, range, assets);
    }
    return constantTexture(ValueTraits<T>::read(json, key, fallback, range));
}

}  // namespace

TexturePtr<float> readFloatTexture(ObjectReader& json, const std::string& key,
                                   const AssetResolver& assets) {
    const KeySpec& spec = json.spec(key);
    std::optional<float> fallback;
    if (spec.fallback.is_number()) fallback = spec.fallback.get<float>();
    return readTexture<float>(json, key, fallback, spec.range, assets);
}

TexturePtr<Rgb> readRgbTexture(ObjectReader& json, const std::string& key,
                               const AssetResolver& assets) {
    const KeySpec& spec = json.spec(key);
    std::optional<Rgb> fallback;
    if (spec.fallback.is_number()) fallback = Rgb(spec.fallback.get<float>());
    return readTexture<Rgb>(json, key, fallback, spec.range, assets);
}

TexturePtr<Rgb> readRgbTexture(ObjectReader& json, const std::string& key, const Rgb& fallback,
                               const AssetResolver& assets) {
    return readTexture<Rgb>(json, key, fallback, json.spec(key).range, assets);
}

KeySpec squaresKey() {
    return key("squares")
        .numbers(2, Range::closed(1, 1e6))
        .byDefault({8, 8})
        .means("[nu, nv] integers: squares along u and v");
}

std::vector<std::pair<std::string, const KeyTable*>> textureTypeKeys() {
    return typeKeys(textureTypes<float>());  // colour textures take the same keys
}

Checkerboard readCheckerboard(ObjectReader& json) {
    const auto squares = json.numbers("squares");
    if (squares[0] != std::floor(squares[0]) || squares[1] != std::floor(squares[1]))
        json.fail("squares", "expected two integers");
    return {int(squares[0]), int(squares[1])};
}

}  // namespace rr
