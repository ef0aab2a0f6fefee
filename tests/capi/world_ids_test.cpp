// The C API's light ids at the end of their range, from inside (the C API's
// own source compiled in, so a world can start near INT_MAX instead of after
// two billion adds): the last id is given, then add_light refuses by name,
// and no id is ever given twice.
#include <gtest/gtest.h>

#include "../../capi/src/isolux_c.cpp"

TEST(CapiLightIds, addLightRefusesOnceIdsReachIntMaxAndNeverReusesOne) {
    isolux_world* w = nullptr;
    ASSERT_EQ(isolux_world_open_seeded("isolux", 4, 4, nullptr, nullptr, &w), ISOLUX_OK) << isolux_last_error();
    w->next_id = INT_MAX - 2;  // as after 2^31 - 3 adds
    isolux_light l;
    isolux_light_init(&l, 100, 100);
    int a = 0, b = 0, c = 0;
    ASSERT_EQ(isolux_world_add_light(w, &l, &a), ISOLUX_OK);
    ASSERT_EQ(isolux_world_add_light(w, &l, &b), ISOLUX_OK);
    EXPECT_EQ(a, INT_MAX - 2);
    EXPECT_EQ(b, INT_MAX - 1);
    ASSERT_EQ(isolux_world_remove_light(w, a), ISOLUX_OK);  // a freed id is not given again
    EXPECT_EQ(isolux_world_add_light(w, &l, &c), ISOLUX_ERROR_INPUT);
    EXPECT_NE(std::string(isolux_last_error()).find("every light id"), std::string::npos) << isolux_last_error();
    int ids[4], count = 0;
    ASSERT_EQ(isolux_world_lights(w, ids, 4, &count), ISOLUX_OK);
    EXPECT_EQ(count, 1);  // the refused add left the world as it was
    EXPECT_EQ(ids[0], INT_MAX - 1);
    isolux_world_free(w);
}
