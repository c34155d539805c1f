// The lab's reports in-process: JSON lines, the JSON object's keys, the median,
// the summary, the CSV dump of a hand-built world, and the atomic write.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "json.h"
#include "lab_test_util.h"
#include "report.h"
#include "run.h"
#include "text.h"

namespace {

using lab_testing::parseFlatJson;

// Every JSON the lab writes goes through jsonLine: one line, numbers that read back the same
// double, null for what is not finite, and a name in another encoding replaced, not thrown on.
TEST(LabReport, JsonLinesRoundTripNumbersAndReplaceWhatJsonCannotHold) {
  lab::Json j;
  j["third"] = 1.0 / 3.0;
  j["two"] = 2.0;
  j["nan"] = std::numeric_limits<double>::quiet_NaN();
  j["inf"] = -std::numeric_limits<double>::infinity();
  j["text"] = "a\"b\\c\ttab\n caf\xc3\xa9";
  j["latin1"] = "caf\xe9";
  const std::string line = lab::jsonLine(j);
  EXPECT_EQ(line.find('\n'), line.size() - 1) << line;
  const auto back = lab::Json::parse(line);
  EXPECT_EQ(back["third"].get<double>(), 1.0 / 3.0);
  EXPECT_EQ(back["two"].dump(), "2.0");
  EXPECT_TRUE(back["nan"].is_null());
  EXPECT_TRUE(back["inf"].is_null());
  EXPECT_EQ(back["text"].get<std::string>(), "a\"b\\c\ttab\n caf\xc3\xa9");
  EXPECT_EQ(back["latin1"].get<std::string>(), "caf\xef\xbf\xbd");  // U+FFFD in place of the byte
}

TEST(LabReport, HashIsSixteenHexDigits) {
  EXPECT_EQ(lab::hexHash(0), "0000000000000000");
  EXPECT_EQ(lab::hexHash(0xcbf29ce484222325ULL), "cbf29ce484222325");
  EXPECT_EQ(lab::hexHash(~0ULL), "ffffffffffffffff");
}

TEST(LabReport, Median) {
  EXPECT_EQ(lab::median({}), 0.0);
  EXPECT_EQ(lab::median({4.0}), 4.0);
  EXPECT_EQ(lab::median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(lab::median({4.0, 1.0, 3.0, 100.0}), 3.5);
}

// The tables' one formatter: printf's widths, and a cell longer than any buffer kept whole.
TEST(LabReport, PrintedFormatsCellsAndNeverCutsThemShort) {
  EXPECT_EQ(lab::printed("%-6s|%6.2e|%3d", "xpbd", 0.000123, 7), "xpbd  |1.23e-04|  7");
  const std::string longName(1000, 'x');
  EXPECT_EQ(lab::printed("[%s]", longName.c_str()), "[" + longName + "]");
}

// Comma lists as the options take them: an empty item anywhere is refused.
TEST(LabReport, SplitListRefusesAnEmptyItemAnywhere) {
  EXPECT_EQ(lab::splitList("a"), std::vector<std::string>{"a"});
  EXPECT_EQ(lab::splitList("1,22,333"), (std::vector<std::string>{"1", "22", "333"}));
  for (const char* bad : {"", ",", "a,", ",a", "a,,b"}) EXPECT_FALSE(lab::splitList(bad)) << bad;
}

TEST(LabReport, JsonHasEveryKeyInOrderEvenWhenFiguresAreNotFinite) {
  lab::RunResult r;
  r.scene = "we\"ird";
  r.steps = 3;
  r.hash = 42;
  r.energyInitial = std::numeric_limits<double>::quiet_NaN();
  r.final.maxSpeed = std::numeric_limits<double>::infinity();
  r.final.kineticEnergy = std::numeric_limits<double>::infinity();
  const std::string json = lab::jsonText(r);
  EXPECT_EQ(json.back(), '\n');
  EXPECT_EQ(json.find('\n'), json.size() - 1) << "one line";
  const auto j = parseFlatJson(json);
  ASSERT_TRUE(j) << json;
  EXPECT_EQ(j->keys, lab_testing::kRunJsonKeys);
  EXPECT_EQ(j->values.at("energy_initial"), "null");
  EXPECT_EQ(j->values.at("max_speed"), "null");
  EXPECT_EQ(j->values.at("energy_final"), "null");
  EXPECT_EQ(j->values.at("scene"), "\"we\\\"ird\"");
  EXPECT_EQ(j->values.at("hash"), "\"000000000000002a\"");
}

// A run at 1000 x 1000 on the pile took minutes a step with nothing shown; a long run now says
// where it is. Timed from zero here, so every step reports.
TEST(LabReport, ALongRunSaysHowFarItHasGot) {
  scenes::Scene scene = scenes::loadSceneText("<scene name=\"s\"><particle pos=\"0 1 0\"/></scene>", "s.xml");
  lab::RunOptions options;
  options.steps = 3;
  std::ostringstream progress;
  lab::runScene(scene, options, &progress, {0.0, 0.0});
  const std::string lines = progress.str();
  EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), 3) << lines;
  EXPECT_EQ(lines.rfind("lab: run: step 1 of 3, ", 0), 0u) << lines;
  EXPECT_NE(lines.find("lab: run: step 3 of 3, "), std::string::npos) << lines;
  EXPECT_NE(lines.find("about 0 s left"), std::string::npos) << lines;
  // With the default timing a short run says nothing.
  std::ostringstream quiet;
  lab::runScene(scene, options, &quiet);
  EXPECT_EQ(quiet.str(), "");
}

TEST(LabReport, SummaryNamesStagesFreezesAndHash) {
  lab::RunResult r;
  r.scene = std::string("s");
  r.steps = 2;
  r.hash = 0xabc;
  // Every stage a different time, so a stage printed under another's name shows.
  for (std::size_t i = 0; i < phys::kStageCount; ++i) r.stageSums.stage[i] = static_cast<double>(i + 1);
  r.stageSums.total = 160.0;  // 136 in the stages, 24 left over
  r.medianStepMs = 8.0;
  r.final.frozen = 1;
  r.freezes.push_back({"runaway", "left the world bound of 10 m", phys::ParticleId{0}, 0.25});
  const std::string s = lab::summaryText(r);
  for (const char* part : {"median 8 ms",
                           "animate       1 ms",
                           "integrate     2 ms (1.25%)",
                           "frames        3 ms",
                           "broad-phase   4 ms",
                           "sweep         5 ms",
                           "narrow-phase  6 ms",
                           "parting       7 ms",
                           "sticks        8 ms",
                           "links         9 ms",
                           "contacts      10 ms",
                           "friction      11 ms",
                           "velocities    12 ms",
                           "restitution   13 ms",
                           "body-damping  14 ms",
                           "guard         15 ms (9.38%)",
                           "islands       16 ms (10%)",
                           "other         24 ms (15%)",
                           "runaway: left the world bound of 10 m",
                           "t=0.25 s",
                           "0000000000000abc"}) {
    EXPECT_NE(s.find(part), std::string::npos) << part << "\n" << s;
  }
}

// A character's drives that ran away printed "head blew up/blew up" part by part (and "n/a/12" for a
// torque that was no number); the summary says it once a character, in words, without a unit after.
TEST(LabReport, DrivesThatAreNotFiniteAreSaidInWords) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  lab::RunResult r;
  r.scene = "s";
  r.drives = {{"steady", "torso", true, 1.0, 2.0, 3.0, 4.0},
              {"steady", "head", false, 0.5, 0.75},
              {"steady", "neck", false, 0.25, 1.5},
              {"wild", "torso", true, 1.0, 2.0, inf, inf},
              {"wild", "head", false, inf, inf},
              {"odd", "torso", true, 1.0, 2.0, 3.0, 4.0},
              {"odd", "head", false, nan, 12.0}};
  const std::string s = lab::summaryText(r);
  EXPECT_NE(s.find("             steady: torso (root) 3/4 N and 1/2 N m; head 0.5/0.75, neck 0.25/1.5 N m\n"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("             wild: blew up\n"), std::string::npos) << s;
  EXPECT_NE(s.find("             odd: n/a\n"), std::string::npos) << s;
  EXPECT_EQ(s.find("blew up/"), std::string::npos) << s;
  EXPECT_EQ(s.find("/blew up"), std::string::npos) << s;
  EXPECT_EQ(s.find("n/a/"), std::string::npos) << s;
}

// `lab report`'s table of a run's drives read each figure back as a number: one the JSON holds as null
// (a run that blew up) threw nlohmann's type error out of the whole report.
TEST(LabReport, TheDrivesTableSaysAFigureThatIsNotFiniteInWords) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  lab::RunResult r;
  r.scene = "s";
  r.steps = 60;
  r.solver.dt = 1.0 / 60.0;
  r.drives = {{"r", "torso", true, 1.0, 2.0, inf, inf}, {"r", "head", false, 0.5, inf}};
  std::string md;
  ASSERT_NO_THROW(md = lab::drivesTable("s", lab::jsonText(r)));
  EXPECT_NE(md.find("| torso (root: hand of god) | blew up, 1 N m | blew up, 2 N m |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| head | 0.5 N m | blew up |"), std::string::npos) << md;
}

TEST(LabReport, DumpHasHeaderAndOneRowPerNamedBody) {
  phys::WorldSettings ws;
  ws.ground = false;
  phys::World world(ws);
  phys::BodyDesc box;
  box.center = {1.0, 2.0, 3.0};
  const phys::BodyId b = world.addBody(box);
  world.addParticle({{0.0, 0.0, 0.0}, phys::Vec3(0.0), 1.0});  // unnamed: not dumped
  const phys::ParticleId p = world.addParticle({{4.0, 5.0, 6.0}, phys::Vec3(0.0), 1.0});
  const std::vector<scenes::NamedBody> bodies = {{"crate", scenes::NamedBody::Kind::Body, b},
                                                 {"p,\"q\"", scenes::NamedBody::Kind::Particle, p}};
  const std::string csv = lab::dumpCsv(world, bodies);
  EXPECT_EQ(csv,
            "name,x,y,z,qw,qx,qy,qz\n"
            "crate,1,2,3,1,0,0,0\n"
            "\"p,\"\"q\"\"\",4,5,6,1,0,0,0\n")
      << csv;
}

}  // namespace
