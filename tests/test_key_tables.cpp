// The key tables (config/key_table.h): a reader takes ranges and defaults from its table,
// refuses to read an undeclared key, and records what it read; the loader's catalogue covers
// every registered type, and estimandOf drops exactly the keys declared estimand-neutral.
#include <gtest/gtest.h>

#include <set>

#include "config/json_reader.h"
#include "loader/scene_keys.h"
#include "loader/scene_loader.h"

namespace rr {
namespace {

const KeyTable kKeys{"test",
                     "",
                     {key("count").integer(Range::closed(1, 8)).byDefault(2).means("a count"),
                      key("scale").number(Range::positive()).means("required"),
                      key("mode").choice({"a", "b"}).byDefault("a").means("a choice")}};

TEST(KeyTables, DefaultsAndRangesComeFromTheTable) {
    const Json object = {{"scale", 0.5}};
    ObjectReader j(object, "/x", kKeys);
    EXPECT_EQ(j.integer("count"), 2);
    EXPECT_EQ(j.number("scale"), 0.5);
    EXPECT_EQ(j.choice("mode"), "a");
    j.finish();
    EXPECT_EQ(j.values(), (Json{{"count", 2}, {"scale", 0.5}, {"mode", "a"}}));

    const Json bad = {{"count", 9}, {"scale", 1}};
    ObjectReader k(bad, "/x", kKeys);
    try {
        k.integer("count");
        FAIL() << "9 is outside [1, 8]";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.pointer(), "/x/count");
    }
    const Json missing = Json::object();
    ObjectReader m(missing, "/x", kKeys);
    try {
        m.number("scale");
        FAIL() << "a key without a default is required";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.pointer(), "/x/scale");
    }
}

TEST(KeyTables, AnUndeclaredKeyIsAProgrammingError) {
    const Json object = {{"scale", 1}};
    ObjectReader j(object, "/x", kKeys);
    EXPECT_THROW(j.has("colour"), std::logic_error);
    EXPECT_THROW(j.getNumber("colour", 1.0), std::logic_error);
}

TEST(KeyTables, TheCatalogueHasEveryTableItRefersTo) {
    const KeyCatalogue& c = sceneKeys();
    std::set<std::string> names;
    for (const KeyTable* t : c.tables)
        EXPECT_TRUE(names.insert(t->name).second) << t->name << " listed twice";
    for (const KeyTable* t : c.tables)
        for (const KeySpec& k : t->keys) {
            if (k.kind == KeyKind::Object) {
                EXPECT_TRUE(c.table(k.refers)) << t->name << "/" << k.name;
            }
            if (k.kind == KeyKind::OneOf || k.kind == KeyKind::ListOf || k.kind == KeyKind::MapOf) {
                EXPECT_TRUE(c.category(k.refers)) << t->name << "/" << k.name;
            }
            EXPECT_FALSE(k.meaning.empty()) << t->name << "/" << k.name << " has no meaning";
        }
    for (const char* type : {"path", "path_mis", "direct", "tais", "ris", "two_stage", "pmc_ip"})
        EXPECT_TRUE(c.table(std::string("integrator/") + type)) << type;
}

TEST(KeyTables, TheEstimandLeavesOutExactlyTheNeutralKeys) {
    const Json document = {
        {"description", "d"},
        {"render", {{"spp", 4}, {"seed", 3}, {"max_depth", 5}, {"light_selection", "uniform"}}},
        {"camera", {{"position", {0, 0, 1}}, {"look_at", {0, 0, 0}}}},
        {"shapes", Json::array()},
        {"lights",
         {{{"type", "environment"}, {"radiance", 1}, {"sampling", "cosine"}},
          {{"type", "point"}, {"position", {0, 1, 0}}, {"intensity", 1}}}}};
    const Json expected = {{"render", {{"max_depth", 5}}},
                           {"camera", {{"position", {0, 0, 1}}, {"look_at", {0, 0, 0}}}},
                           {"shapes", Json::array()},
                           {"lights",
                            {{{"type", "environment"}, {"radiance", 1}},
                             {{"type", "point"}, {"position", {0, 1, 0}}, {"intensity", 1}}}}};
    EXPECT_EQ(estimandOf(document), expected);
}

}  // namespace
}  // namespace rr
