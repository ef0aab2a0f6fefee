// The parameter table: every row, tested the same way, so a new row is tested
// the moment it is added.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "isolux/params.hpp"
#include "isolux/world.hpp"
#include "test_util.hpp"

using namespace isolux;

namespace {

// The smallest and largest accepted values of a row.
double lowest(const ParamInfo& info) {
    return info.min_open ? std::nextafter(info.min, HUGE_VAL) : info.min;
}
double highest(const ParamInfo& info) { return info.max; }

// One step outside the range: the next integer, or the next double.
double below(const ParamInfo& info) {
    if (info.min_open) return info.min;
    return info.type == ParamType::real ? std::nextafter(info.min, -HUGE_VAL) : info.min - 1;
}
double above(const ParamInfo& info) {
    return info.type == ParamType::real ? std::nextafter(info.max, HUGE_VAL) : info.max + 1;
}

// A value one step from the default, inside the range.
double neighbour(const ParamInfo& info) {
    const double d = param_default(info);
    switch (info.type) {
        case ParamType::boolean: return d != 0 ? 0 : 1;
        case ParamType::choice: return double((int(d) + 1) % choice_count(info));
        case ParamType::integer: return d + 1 <= info.max ? d + 1 : d - 1;
        case ParamType::real: return d + 0.1 <= info.max ? d + 0.1 : d - 0.1;
    }
    return d;
}

bool names(const Error& e, const ParamInfo& info) {
    return std::string(e.what()).find(info.name) != std::string::npos;
}

std::string stage_list(StageSet s) {
    std::string out;
    for (int k = 0; k < stage_count; ++k)
        if (s.has(Stage(k))) out += std::string(to_string(Stage(k))) + " ";
    return out;
}

}  // namespace

TEST(ParamTable, namesAreUniqueAndFlagsAreTheNamesWithDashes) {
    std::set<std::string> seen_names, seen_flags;
    for (const ParamInfo& info : param_table()) {
        EXPECT_TRUE(seen_names.insert(info.name).second) << info.name;
        std::string flag = "--" + std::string(info.name);
        for (char& c : flag)
            if (c == '_') c = '-';
        EXPECT_EQ(flag, info.flag);
        EXPECT_TRUE(seen_flags.insert(info.flag).second) << info.flag;
        if (info.old_flag) {
            EXPECT_TRUE(seen_flags.insert(info.old_flag).second) << info.old_flag;
        }
        EXPECT_NE(std::string(info.help), "") << info.name;
        EXPECT_EQ(find_param(info.name), &info);
        EXPECT_NO_THROW(check_param(info, param_default(info), "defaults")) << info.name;
    }
    EXPECT_EQ(find_param("no_such_parameter"), nullptr);
}

TEST(ParamTable, everyRowRoundTripsThroughSetAndGetAtBothEndsOfItsRange) {
    for (const ParamInfo& info : param_table())
        for (double v : {lowest(info), highest(info)}) {
            Params p;
            set_param(p, info.name, format_param(info, v), "test");
            EXPECT_EQ(info.get(p), v) << info.name;
            EXPECT_EQ(get_param(p, info.name), format_param(info, v)) << info.name;
        }
}

TEST(ParamTable, oneStepBeyondEitherEndIsRefusedNamingTheField) {
    for (const ParamInfo& info : param_table()) {
        std::vector<std::string> bad;
        if (info.type == ParamType::integer || info.type == ParamType::real)
            bad = {format_param(info, below(info)), format_param(info, above(info))};
        else if (info.type == ParamType::choice)
            bad = {"no_such_choice", std::to_string(choice_count(info))};
        else
            bad = {"maybe", "2"};
        for (const std::string& text : bad) {
            Params p;
            try {
                set_param(p, info.name, text, "test");
                ADD_FAILURE() << info.name << " accepted " << text;
            } catch (const Error& e) {
                EXPECT_TRUE(names(e, info)) << e.what();
            }
            EXPECT_EQ(p, Params{}) << "a refused value changed " << info.name;
        }
    }
}

TEST(ParamTable, validateCatchesEveryRowFilledByHandOutOfRange) {
    // What a game that fills Params itself can do: validate (and render_frame) say which field.
    for (const ParamInfo& info : param_table()) {
        if (info.type == ParamType::boolean) continue;  // a bool has no value out of range
        for (double v : {below(info), above(info)}) {
            if (info.type == ParamType::choice && v < 0) continue;
            Params p;
            info.set(p, v);
            try {
                validate(p, "game");
                ADD_FAILURE() << info.name << " = " << v << " passed validate";
            } catch (const Error& e) {
                EXPECT_TRUE(names(e, info)) << e.what();
            }
        }
    }
}

TEST(ParamTable, everyRowRoundTripsThroughPresetAndSceneJsonAtBothEnds) {
    for (const ParamInfo& info : param_table())
        for (double v : {lowest(info), highest(info)}) {
            Params p;
            info.set(p, v);
            EXPECT_EQ(preset_from_json(preset_to_json(p), "p.json"), p) << info.name << " = " << v;
            Scene s;
            s.params = p;
            EXPECT_EQ(scene_from_json(scene_to_json(s), "s.json").params, p) << info.name << " = " << v;
        }
}

TEST(ParamTable, aPresetFieldBeyondItsRangeIsRefusedNamingFileAndField) {
    for (const ParamInfo& info : param_table()) {
        std::vector<std::string> bad;
        if (info.type == ParamType::integer)
            bad = {std::to_string((long long)below(info)), std::to_string((long long)above(info))};
        else if (info.type == ParamType::real)
            bad = {format_param(info, below(info)), format_param(info, above(info))};
        else if (info.type == ParamType::choice)
            bad = {"\"no_such_choice\""};
        else
            bad = {"2"};
        for (const std::string& value : bad) {
            const std::string text = "{\"schema_version\": 1, \"" + std::string(info.name) + "\": " + value + "}";
            try {
                preset_from_json(text, "tuned.json");
                ADD_FAILURE() << text << " was accepted";
            } catch (const Error& e) {
                EXPECT_TRUE(names(e, info)) << e.what();
                EXPECT_NE(std::string(e.what()).find("tuned.json"), std::string::npos) << e.what();
            }
        }
    }
}

TEST(ParamTable, changingARowReRunsExactlyTheStagesItNames) {
    Scene scene;
    scene.width = scene.height = 8;
    scene.params.area_a = scene.params.area_b = 24;  // small, so every_pixel is quick
    const World world = make_world(test::default_tileset(), scene);
    scene.lights = {Light{double(world.placed.bounds.x + world.placed.bounds.w / 2),
                          double(world.placed.bounds.y + world.placed.bounds.h / 2)}};
    for (const ParamInfo& info : param_table()) {
        FrameState st;
        render_frame(st, world, scene, Camera{}, 0);
        Scene changed = scene;
        info.set(changed.params, neighbour(info));
        ASSERT_NE(changed.params, scene.params) << info.name;
        const FrameReport rep = render_frame(st, world, changed, Camera{}, 1);
        StageSet ran;
        for (int k = 0; k < stage_count; ++k)
            if (rep.ran[k]) ran = ran.with(Stage(k));
        EXPECT_EQ(ran, info.reruns) << info.name << ": ran " << stage_list(ran) << "; the table says "
                                    << stage_list(info.reruns);
        // And a frame after it, with nothing changed, runs nothing.
        const FrameReport still = render_frame(st, world, changed, Camera{}, 2);
        for (int k = 0; k < stage_count; ++k) EXPECT_FALSE(still.ran[k]) << info.name << " " << to_string(Stage(k));
    }
}

TEST(ParamTable, renderFrameRefusesParamsOutOfRangeInsteadOfDividingByZero) {
    Scene scene;
    scene.width = scene.height = 4;
    const World world = make_world(test::default_tileset(), scene);
    scene.params.trace_every = 0;
    FrameState st;
    try {
        render_frame(st, world, scene, Camera{}, 0);
        ADD_FAILURE() << "trace_every = 0 was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("trace_every"), std::string::npos) << e.what();
    }
}

TEST(ParamTable, jsonNumbersBeyondADoubleAreAnErrorNotAnAbort) {
    try {
        preset_from_json("{\"schema_version\": 1, \"delta_y\": 1e999}", "huge.json");
        ADD_FAILURE() << "1e999 was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("huge.json"), std::string::npos) << e.what();
    }
}
