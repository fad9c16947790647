#include "loader/scene_loader.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "loader/factories.h"
#include "loader/type_table.h"
#include "render/renderer.h"

namespace rr {

namespace fs = std::filesystem;

namespace {

// Parses `text`, rejecting duplicate keys in any object (nlohmann keeps the last one silently):
// a ConfigError at `base` + the JSON pointer of the duplicate. The parser callback sees the
// document as a stream of events; a stack of the open containers, each with its current
// element index (arrays) or the keys seen so far and the current key (objects), gives the
// pointer of every key.
Json parseRejectingDuplicateKeys(const std::string& text, const std::string& base,
                                 bool ignoreComments) {
    struct Container {
        bool isArray = false;
        size_t index = 0;            // arrays: index of the element being parsed
        std::set<std::string> keys;  // objects: keys seen so far
        std::string key;             // objects: the key of the value being parsed
    };
    std::vector<Container> containers;
    auto pointerOfCurrent = [&] {
        std::string pointer = base;
        for (const Container& c : containers)
            pointer += "/" + (c.isArray ? std::to_string(c.index) : escapePointerToken(c.key));
        return pointer;
    };
    auto elementDone = [&] {
        if (!containers.empty() && containers.back().isArray) ++containers.back().index;
    };
    const Json::parser_callback_t callback = [&](int, Json::parse_event_t event, Json& parsed) {
        switch (event) {
            case Json::parse_event_t::object_start:
            case Json::parse_event_t::array_start:
                containers.push_back({event == Json::parse_event_t::array_start, 0, {}, {}});
                break;
            case Json::parse_event_t::object_end:
            case Json::parse_event_t::array_end:
                containers.pop_back();
                elementDone();
                break;
            case Json::parse_event_t::key: {
                Container& object = containers.back();
                object.key = parsed.get<std::string>();
                if (!object.keys.insert(object.key).second)
                    throw ConfigError(pointerOfCurrent(), "duplicate key");
                break;
            }
            case Json::parse_event_t::value:
                elementDone();
                break;
        }
        return true;
    };
    return Json::parse(text, callback, /*allow_exceptions=*/true, ignoreComments);
}

}  // namespace

Json parseSceneText(const std::string& text, const std::string& sourceName) {
    try {
        return parseRejectingDuplicateKeys(text, "", /*ignoreComments=*/true);
    } catch (const Json::parse_error& e) {
        // Convert nlohmann's byte offset into a line and column.
        size_t line = 1, column = 1;
        for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
            if (text[i] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        throw ConfigError("", "malformed JSON in " + sourceName + " at line " +
                                  std::to_string(line) + ", column " + std::to_string(column));
    }
}

Json readSceneFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ConfigError("", "cannot open scene file " + file.string());
    std::ostringstream text;
    text << in.rdbuf();
    return parseSceneText(text.str(), file.string());
}

void applyOverride(Json& document, const std::string& assignment) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || assignment.empty() || assignment[0] != '/')
        throw ConfigError("", "--set expects /json/pointer=value, got \"" + assignment + "\"");
    const std::string pointerText = assignment.substr(0, eq);
    const std::string valueText = assignment.substr(eq + 1);
    Json value;
    try {
        value = parseRejectingDuplicateKeys(valueText, pointerText, /*ignoreComments=*/false);
    } catch (const Json::parse_error&) {
        value = valueText;  // bare words are strings: --set /integrator/type=path
    }
    try {
        const Json::json_pointer pointer(pointerText);
        if (!document.contains(pointer.parent_pointer()))
            throw ConfigError(
                pointerText,
                "--set: the parent " + pointer.parent_pointer().to_string() + " does not exist");
        Json& parent = document[pointer.parent_pointer()];
        if (parent.is_array()) {
            const std::string last = pointer.back();
            size_t index = 0;
            const char* end = last.data() + last.size();
            const auto [stop, ec] = std::from_chars(last.data(), end, index);
            // from_chars takes digits only (no sign, no space) and reports overflow.
            if (last.empty() || ec != std::errc() || stop != end || index >= parent.size())
                throw ConfigError(pointerText, "--set: not an existing array index");
        } else if (!parent.is_object()) {
            throw ConfigError(pointerText, "--set: the parent is neither an object nor an array");
        }
        document[pointer] = value;
    } catch (const Json::exception& e) {
        throw ConfigError(pointerText,
                          std::string("--set: invalid JSON pointer (") + e.what() + ")");
    }
}

namespace {

constexpr double kMaxPixels = 67108864.0;  // 2^26

RenderSettings readRenderSettings(ObjectReader& j, PathSettings* path) {
    RenderSettings r;
    if (j.has("resolution")) {
        const auto res = j.getNumbers("resolution", 2, Range::closed(1, 16384));
        if (res[0] != std::floor(res[0]) || res[1] != std::floor(res[1]))
            j.fail("resolution", "expected two integers");
        // The film holds several floats per pixel and the EXR a copy: 2^26 pixels (e.g.
        // 8192 × 8192) keep both within a few GB.
        if (res[0] * res[1] > kMaxPixels)
            j.fail("resolution", "width × height = " + std::to_string(int64_t(res[0] * res[1])) +
                                     " pixels exceeds the limit of 2^26 = " +
                                     std::to_string(int64_t(kMaxPixels)));
        r.width = static_cast<int>(res[0]);
        r.height = static_cast<int>(res[1]);
    }
    r.spp = static_cast<uint32_t>(j.getInt("spp", 16, Range::closed(1, kMaxSpp)));
    r.seed = static_cast<uint32_t>(j.getInt("seed", 0, Range::closed(0, 4294967295.0)));
    const std::string sampler =
        j.getChoice("sampler", {"independent", "stratified", "hammersley"}, "independent");
    parseSamplerType(sampler, &r.sampler);
    path->maxDepth = static_cast<int>(j.getInt("max_depth", 16, Range::closed(-1, 100000)));
    path->rrDepth = static_cast<int>(j.getInt("rr_depth", 4, Range::closed(1, 100000)));
    r.lightSelection = j.getChoice("light_selection", {"power", "uniform"}, "power") == "uniform"
                           ? LightSelection::Uniform
                           : LightSelection::Power;
    j.finish();
    return r;
}

CameraSettings readCamera(ObjectReader& j) {
    CameraSettings c;
    const std::string type = j.getChoice("type", {"pinhole", "thin_lens"}, "pinhole");
    c.position = j.getVec3("position");
    c.lookAt = j.getVec3("look_at");
    c.up = j.getVec3("up", Vec3(0, 1, 0));
    c.verticalFovDegrees = j.getFloat("fov", 40.0f, Range::open(0, 180));
    const Vec3 forward = c.lookAt - c.position;
    if (!(length(forward) > 0)) j.fail("look_at", "must differ from the camera position");
    if (!(length(c.up) > 0)) j.fail("up", "expected a non-zero vector");
    c.up = normalize(c.up);  // only its direction matters: a tiny up is as good as a unit one
    if (!(length(cross(normalize(forward), c.up)) > 1e-4f))
        j.fail("up", "must not be parallel to the viewing direction");
    if (type == "thin_lens") {
        c.apertureRadius = j.getFloat("aperture_radius", Range::positive());
        c.focusDistance = j.getFloat("focus_distance", Range::positive());
    }
    if (j.has("shutter")) {
        const auto s = j.getNumbers("shutter", 2, Range::unit());
        if (s[0] > s[1]) j.fail("shutter", "expected [open, close] with open <= close");
        c.shutterOpen = static_cast<float>(s[0]);
        c.shutterClose = static_cast<float>(s[1]);
    }
    j.finish();
    return c;
}

// The named material table and inline materials. Named materials are built on first
// reference, so that mix and checker materials may refer to any entry of the table whatever
// its order, and every entry is built once; a chain of references that returns to a material
// being built is an error.
class MaterialCatalog {
  public:
    MaterialCatalog(const Json* table, const std::string& pointer, SceneBuilder& builder,
                    const AssetResolver& assets)
        : table_(table), pointer_(pointer), builder_(builder), assets_(assets) {
        if (!table) return;
        if (!table->is_object()) throw ConfigError(pointer, "expected an object of materials");
        for (const auto& item : table->items())  // unreferenced entries are checked too
            named(item.key(), pointer);
    }

    // A material reference at `pointer`: a name from the table or an inline object.
    const Material* resolve(const Json& reference, const std::string& pointer) {
        if (reference.is_object()) return build(reference, pointer);
        if (!reference.is_string())
            throw ConfigError(pointer, "expected a material name or object");
        return named(reference.get<std::string>(), pointer);
    }

    // A shape's "material".
    const Material* resolve(ObjectReader& shape) {
        return resolve(shape.raw("material"), shape.pointerTo("material"));
    }

  private:
    const Material* named(const std::string& name, const std::string& referrer) {
        if (const auto it = named_.find(name); it != named_.end()) {
            if (!it->second)
                throw ConfigError(referrer, "material \"" + name + "\" refers back to itself");
            return it->second;
        }
        if (!table_ || !table_->contains(name))
            throw ConfigError(referrer, "no material named \"" + name + "\" in /materials");
        named_[name] = nullptr;  // being built
        const Material* material =
            build(table_->at(name), pointer_ + "/" + escapePointerToken(name));
        named_[name] = material;
        return material;
    }

    const Material* build(const Json& description, const std::string& pointer) {
        ObjectReader m(description, pointer);
        const MaterialReferences references = [this](const Json& ref, const std::string& at) {
            return resolve(ref, at);
        };
        return builder_.addMaterial(makeMaterial(m, assets_, references));
    }

    const Json* table_;
    std::string pointer_;
    SceneBuilder& builder_;
    const AssetResolver& assets_;
    std::map<std::string, const Material*> named_;  // nullptr while being built
};

void readShape(ObjectReader& j, MaterialCatalog& materials, SceneBuilder& builder,
               const AssetResolver& assets, const CameraSettings& camera) {
    Transform transform = readTransform(j, "transform");

    Rgb emission(0.0f);
    bool twoSided = false;
    if (const Json* e = j.rawOptional("emission")) {
        ObjectReader ej(*e, j.pointerTo("emission"));
        emission = ej.getRgb("radiance");
        twoSided = ej.getBool("two_sided", false);
        ej.finish();
    }
    const Medium* interior = nullptr;
    if (const Json* m = j.rawOptional("interior_medium")) {
        ObjectReader mj(*m, j.pointerTo("interior_medium"));
        interior = builder.addMedium(makeMedium(mj));
    }
    const Material* material = nullptr;
    if (j.has("material"))
        material = materials.resolve(j);
    else if (emission.isBlack() && !interior)
        j.fail("material",
               "missing required key (only emitters and medium boundaries may omit a material)");

    Vec3 motion(0.0f);
    if (const Json* m = j.rawOptional("motion")) {
        ObjectReader mj(*m, j.pointerTo("motion"));
        motion = mj.getVec3("translate");
        mj.finish();
    }
    // Without a shutter interval a moving shape is frozen where it is at the shutter instant,
    // so the scene pays nothing for motion blur.
    const bool shutterOpenInterval = camera.shutterClose > camera.shutterOpen;
    if (!shutterOpenInterval)
        transform = transform.then(Transform::translate(motion * camera.shutterOpen));

    // The geometry is read last: the factory's finish() then rejects unknown keys for the
    // whole shape object, including the common keys read above.
    std::unique_ptr<Shape> shape = makeShape(j, transform, assets);
    if (!(shape->area() > 0) || !std::isfinite(shape->area()))
        j.fail("type", "the shape has zero or non-finite area");
    if (shutterOpenInterval) shape->setMotion(motion);
    shape->setInteriorMedium(interior);
    builder.addShape(std::move(shape), material, emission, twoSided);
}

// The structured samplers index a pixel's spp × repeats draws of one decision in 32 bits, and
// the float sample count is exact to kMaxSpp: the product is bounded by it too.
void checkStructuredSampleCount(const RenderSettings& render, const Integrator& integrator,
                                const std::string& sppPointer) {
    const uint64_t repeats = integrator.decisionRepeats();
    const uint64_t product = uint64_t(render.spp) * repeats;
    if (product > kMaxSpp)
        throw ConfigError(
            sppPointer,
            "spp (" + std::to_string(render.spp) + ") × the " + std::to_string(repeats) +
                " draws per sample of the integrator's decisions = " + std::to_string(product) +
                " exceeds 2^24 = " + std::to_string(kMaxSpp));
}

}  // namespace

LoadedScene loadScene(const Json& document, const AssetResolver& assets) {
    ObjectReader root(document, "");
    root.getString("description", "");

    PathSettings path;
    RenderSettings render;
    {
        static const Json empty = Json::object();
        const Json* r = root.rawOptional("render");
        ObjectReader rj(r ? *r : empty, root.pointerTo("render"));
        render = readRenderSettings(rj, &path);
    }

    SceneBuilder builder;
    CameraSettings camera;
    {
        ObjectReader cj(root.raw("camera"), root.pointerTo("camera"));
        camera = readCamera(cj);
    }
    builder.setCamera(camera, render.width, render.height);

    // Where the first medium is declared, for the error if the integrator cannot render it.
    std::string mediumPointer;
    if (const Json* m = root.rawOptional("medium")) {
        ObjectReader mj(*m, root.pointerTo("medium"));
        builder.setSceneMedium(builder.addMedium(makeMedium(mj)));
        mediumPointer = mj.pointer();
    }

    MaterialCatalog materials(root.rawOptional("materials"), root.pointerTo("materials"), builder,
                              assets);

    const Json& shapes = root.raw("shapes");
    if (!shapes.is_array()) root.fail("shapes", "expected an array of shapes");
    for (size_t i = 0; i < shapes.size(); ++i) {
        ObjectReader sj(shapes[i], root.pointerTo("shapes") + "/" + std::to_string(i));
        readShape(sj, materials, builder, assets, camera);
        if (mediumPointer.empty() && shapes[i].contains("interior_medium"))
            mediumPointer = sj.pointerTo("interior_medium");
    }

    if (const Json* lights = root.rawOptional("lights")) {
        if (!lights->is_array()) root.fail("lights", "expected an array of lights");
        for (size_t i = 0; i < lights->size(); ++i) {
            ObjectReader lj((*lights)[i], root.pointerTo("lights") + "/" + std::to_string(i));
            builder.addLight(makeLight(lj, assets));
        }
    }

    std::unique_ptr<Integrator> integrator;
    {
        static const Json defaultIntegrator = {{"type", "path_mis"}};
        const Json* ij = root.rawOptional("integrator");
        ObjectReader reader(ij ? *ij : defaultIntegrator, root.pointerTo("integrator"));
        integrator = makeIntegrator(reader, path);
    }
    checkStructuredSampleCount(render, *integrator, root.pointerTo("render") + "/spp");
    if (!mediumPointer.empty() && !integrator->supportsMedia())
        throw ConfigError(mediumPointer, "the " + integrator->name() +
                                             " integrator does not render participating media; "
                                             "use \"path\" or \"path_mis\"");
    root.finish();

    LoadedScene loaded;
    loaded.scene = builder.build(render.lightSelection);
    if (loaded.scene->lights().empty())
        throw ConfigError("", "the scene has no light: add an emitter shape or a light");
    integrator->prepare(*loaded.scene);
    loaded.integrator = std::move(integrator);
    loaded.render = render;
    return loaded;
}

}  // namespace rr
