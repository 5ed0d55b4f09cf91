// Scripts of timed commands (app/playback/view_script.h) and the debug-view names they use
// (sss/debug_view.h): what a valid file holds, and the exact FILE:LINE:COL line of each mistake.
#include "app/playback/view_script.h"

#include <gtest/gtest.h>

#include "support/error_of.h"

#include "app/config/input_error.h"
#include "app/config/params.h"

namespace tallow::app {
namespace {

constexpr const char* kCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"
    "White Grapefruit Juice,Narasimhan et al. 2006,0.3513,0.3669,0.5237,0.0096,0.0131,0.0395,0.548,0.545,0.565,1.3,mm^-1\n";

const Registry& registry() {
  static const sss::MaterialTable table = sss::MaterialTable::parse(kCsv, "inline.csv");
  static const Registry r = parameterRegistry(table);
  return r;
}

Script parse(const std::string& text) { return parseScript(text, "s.txt", registry()); }
std::string errorOf(const std::string& text) { return test::errorOf<InputError>([&] { parse(text); }); }

TEST(ViewScript, ReadsEveryCommand) {
  const Script s = parse(
      "# a comment line\n"
      "\n"
      "frame 0 set sss.maps=4\n"
      "frame 0   set material=\"White Grapefruit Juice\"   # trailing comment\n"
      "frame 2 set light.intensity = 1, 2.5, 3\n"
      "frame 3 pause\n"
      "frame 3 seek 2.5\n"
      "frame 4 speed -0.5\n"
      "frame 4 loop off\n"
      "frame 5 play\n"
      "frame 6 orbit 30 -10\n"
      "frame 6 pan 0.1 0\n"
      "frame 6 zoom 0.8\n"
      "frame 7 debug gbuffer-normal:1:4\n"
      "frame 8 screenshot shots/a b.png\n"
      "frame 8 save-preset saved.json\n"
      "frame 9 quit\r\n");
  ASSERT_EQ(s.commands.size(), 15u);
  const ScriptCommand& maps = s.commands[0];
  EXPECT_EQ(maps.action, ScriptAction::Set);
  EXPECT_EQ(maps.key, "sss.maps");
  EXPECT_EQ(maps.value, 4);
  EXPECT_EQ(maps.where, "s.txt:3:9");
  EXPECT_EQ(s.commands[1].value, "White Grapefruit Juice");
  EXPECT_EQ(s.commands[2].value, nlohmann::json::array({1.0, 2.5, 3.0}));
  EXPECT_EQ(s.commands[3].action, ScriptAction::Pause);
  EXPECT_EQ(s.commands[4].a, 2.5);
  EXPECT_EQ(s.commands[5].a, -0.5);
  EXPECT_FALSE(s.commands[6].on);
  EXPECT_EQ(s.commands[8].a, 30.0);
  EXPECT_EQ(s.commands[8].b, -10.0);
  EXPECT_EQ(s.commands[10].a, 0.8);
  EXPECT_EQ(s.commands[11].debug.kind, sss::DebugViewKind::GBufferNormal);
  EXPECT_EQ(s.commands[11].debug.light, 1);
  EXPECT_EQ(s.commands[11].debug.layer, 4);
  EXPECT_EQ(s.commands[12].path, "shots/a b.png");
  EXPECT_EQ(s.commands[13].action, ScriptAction::SavePreset);
  EXPECT_EQ(s.commands[14].action, ScriptAction::Quit);
  EXPECT_EQ(s.at(6).size(), 3u);
  EXPECT_EQ(s.at(1).size(), 0u);
  EXPECT_EQ(s.lastFrame(), 9);
}

TEST(ViewScript, MistakesAreLocated) {
  EXPECT_EQ(errorOf("frame 0 set sss.maps=4\nfram 3 pause\n"), "s.txt:2:1: expected \"frame N <command>\", got \"fram\"");
  EXPECT_EQ(errorOf("frame x pause"), "s.txt:1:7: frame number: \"x\" is not a number");
  EXPECT_EQ(errorOf("frame 2.5 pause"), "s.txt:1:7: frame number: expected an integer");
  EXPECT_EQ(errorOf("frame -1 pause"), "s.txt:1:7: frame number: -1 is out of range [0, 1073741824]");
  EXPECT_EQ(errorOf("frame 5 pause\nframe 3 play"), "s.txt:2:7: frame 3 comes after frame 5 (frames must not decrease)");
  EXPECT_EQ(errorOf("frame 1"), "s.txt:1:8: expected a command after the frame number");
  EXPECT_EQ(errorOf("frame 1 pasue"), "s.txt:1:9: unknown command \"pasue\" (did you mean \"pause\"?)");
  EXPECT_EQ(errorOf("frame 1 pause now"), "s.txt:1:15: unexpected \"now\" after pause");
  EXPECT_EQ(errorOf("frame 1 set sss.maps"), "s.txt:1:13: expected key=value after set");
  EXPECT_EQ(errorOf("frame 1 set sss.mpas=4"), "s.txt:1:13: unknown parameter \"sss.mpas\" (did you mean \"sss.maps\"?)");
  EXPECT_EQ(errorOf("frame 1 set sss.maps=0"), "s.txt:1:22: sss.maps: 0 is out of range [1, 256]");
  EXPECT_EQ(errorOf("frame 1 set sss.maps= four"), "s.txt:1:23: sss.maps: \"four\" is neither an integer nor auto");
  EXPECT_EQ(errorOf("frame 1 set sss.samples= four"), "s.txt:1:26: sss.samples: \"four\" is not an integer");
  EXPECT_EQ(errorOf("frame 1 set material=Marbel"),
            "s.txt:1:22: material: unknown value \"Marbel\" (did you mean \"Marble\"?); choices: Marble, White "
            "Grapefruit Juice");
  EXPECT_EQ(errorOf("frame 1 loop maybe"), "s.txt:1:14: loop: expected on or off, got \"maybe\"");
  EXPECT_EQ(errorOf("frame 1 zoom 0"), "s.txt:1:14: zoom factor: 0 is out of range [0.001, 1000]");
  EXPECT_EQ(errorOf("frame 1 orbit 30"), "s.txt:1:17: expected orbit pitch [deg]");
  EXPECT_EQ(errorOf("frame 1 debug maps:2"),
            "s.txt:1:15: debug: unknown debug view \"maps\"; views: final, gbuffer-position, gbuffer-normal, map, "
            "coverage, vpl, wireframe, difference");
  EXPECT_EQ(errorOf("frame 1 debug gbuffer-normal:0:6"), "s.txt:1:15: debug: cube face: expected 0 to 5, got 6");
  EXPECT_EQ(errorOf("frame 1 screenshot a.jpg"), "s.txt:1:20: screenshot: expected a .png or .exr file, got \"a.jpg\"");
  EXPECT_EQ(errorOf("frame 1 save-preset"), "s.txt:1:20: save-preset: expected a file name");
  // Columns count characters, not bytes (the key after a two-byte "é" in a comment-free line).
  EXPECT_EQ(errorOf("frame 1 set ambient=\xC3\xA9"), "s.txt:1:21: ambient: expected three numbers x,y,z, got \"\xC3\xA9\"");
  EXPECT_EQ(errorOf(std::string("frame 1 pause\nframe 2 \0play", 27)), "s.txt:2:9: NUL character (not a text file?)");
}

TEST(ViewScript, KeysAreTheWindowsHotkeys) {
  const Script s = parse("frame 1 key space\nframe 2 key Ctrl+Z\nframe 2 key ctrl+shift+z\nframe 3 key esc\n");
  ASSERT_EQ(s.commands.size(), 4u);
  EXPECT_EQ(s.commands[0].action, ScriptAction::Key);
  EXPECT_EQ(s.commands[0].hotkey, Hotkey::PlayPause);
  EXPECT_EQ(s.commands[1].hotkey, Hotkey::Undo);
  EXPECT_EQ(s.commands[2].hotkey, Hotkey::Redo);
  EXPECT_EQ(s.commands[3].hotkey, Hotkey::Quit);
  EXPECT_EQ(errorOf("frame 1 key"), "s.txt:1:12: key: expected a hotkey, e.g. space or ctrl+z");
  EXPECT_EQ(errorOf("frame 1 key ctrl+x"), "s.txt:1:13: key: unknown hotkey \"ctrl+x\" (did you mean \"ctrl+z\"?)");
  EXPECT_EQ(errorOf("frame 1 key space bar"), "s.txt:1:19: unexpected \"bar\" after key");
  // Every hotkey's script name reads back as that hotkey.
  for (const Hotkey k : allHotkeys()) EXPECT_EQ(parseHotkey(hotkeyName(k)), k) << hotkeyName(k);
}

TEST(DebugView, NamesRoundTrip) {
  for (const char* text : {"final", "gbuffer-position:0:0", "gbuffer-normal:2:5", "map:7", "coverage", "vpl",
                           "wireframe", "difference"})
    EXPECT_EQ(sss::formatDebugView(sss::parseDebugView(text)), text);
  EXPECT_EQ(sss::parseDebugView("map").layer, 0);
  EXPECT_EQ(test::errorOf<std::invalid_argument>([] { sss::parseDebugView("coverage:1"); }),
            "debug view coverage takes no index");
  EXPECT_EQ(test::errorOf<std::invalid_argument>([] { sss::parseDebugView("map:-1"); }),
            "map: expected an integer in [0, 4096], got \"-1\"");
}

}  // namespace
}  // namespace tallow::app
