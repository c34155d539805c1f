// Bad scene files: each error names the file, the line and the attribute, and nothing loads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "bad_scene.h"
#include "physics/rigid_joints.h"
#include "scene_text.h"
#include "scenes/scene.h"
#include "temp_folder.h"
#include "unprivileged.h"

namespace {

using testing_scenes::BadScene;

const BadScene kCases[] = {
    {"unknown element", "<scene name='s'>\n<ground/>\n<boxx pos='0 0 0'/>\n</scene>", 3, "",
     "unknown element"},
    // Said to "take no child elements or text", as if it were an element of the format.
    {"unknown element with content", "<scene name='s'>\n<ground/>\n<boxx pos='0 0 0'>crate</boxx>\n</scene>",
     3, "", "<boxx>: unknown element"},
    {"unknown attribute", "<scene name='s'>\n<box pos='0 1 0'\n colour='red'/>\n</scene>", 3, "colour",
     "unknown attribute"},
    {"missing required attribute", "<scene name='s'>\n\n<box size='1'/>\n</scene>", 3, "pos", "is required"},
    {"malformed vector", "<scene name='s'>\n<box pos='0 1 x'/>\n</scene>", 2, "pos", "three finite numbers"},
    {"two numbers for a vector", "<scene name='s'>\n<box pos='0 1'/>\n</scene>", 2, "pos",
     "three finite numbers"},
    {"NaN", "<scene name='s'>\n<particle pos='0 0 0' mass='nan'/>\n</scene>", 2, "mass",
     "not a finite number"},
    {"infinity", "<scene name='s'>\n<world damping='inf'/>\n</scene>", 2, "damping", "not a finite number"},
    {"junk after a number", "<scene name='s'>\n<solver dt='0.01s'/>\n</scene>", 2, "dt",
     "not a finite number"},
    {"negative size", "<scene name='s'>\n<box pos='0 0 0' size='1 -1 1'/>\n</scene>", 2, "size",
     "sizes must be from 0.001 to 2e+09 (m)"},
    {"negative mass", "<scene name='s'>\n<box pos='0 0 0' mass='-2'/>\n</scene>", 2, "mass",
     "from 1e-06 to 1e+09 (kg)"},
    // Tiny or huge values the physics cannot represent are refused by attribute, not by a
    // message from deep in the physics that names none.
    {"tiny size", "<scene name='s'>\n<box pos='0 0 0' size='1e-300'/>\n</scene>", 2, "size",
     "sizes must be from 0.001"},
    {"tiny mass", "<scene name='s'>\n<box pos='0 0 0' mass='1e-300'/>\n</scene>", 2, "mass", "from 1e-06"},
    {"huge mass", "<scene name='s'>\n<particle pos='0 0 0' mass='1e300'/>\n</scene>", 2, "mass",
     "to 1e+09 (kg)"},
    {"tiny capsule", "<scene name='s'>\n<capsule pos='0 0 0' radius='1e-300' length='1'/>\n</scene>", 2,
     "radius", "at least 0.0005"},
    {"tiny ragdoll", "<scene name='s'>\n<ragdoll pos='0 1 0' scale='1e-300'/>\n</scene>", 2, "scale",
     "from 0.02 to 1000"},
    {"light ragdoll", "<scene name='s'>\n<ragdoll pos='0 1 0' mass='1e-300'/>\n</scene>", 2, "mass",
     "from 2e-05"},
    {"inertia floor above 1",
     "<scene name='s'>\n<ragdoll pos='0 1 0' model='rigid' inertia-floor='1.5'/>\n</scene>", 2,
     "inertia-floor", "'1.5' must be from 0 to 1"},
    {"negative inertia floor",
     "<scene name='s'>\n<box pos='0 1 0' model='rigid' inertia-floor='-0.2'/>\n</scene>", 2, "inertia-floor",
     "must be from 0 to 1"},
    {"light chain end",
     "<scene name='s'>\n<chain pos='0 1 0' links='2' length='1' end-mass='1e-300'/>\n</scene>", 2, "end-mass",
     "from 1e-06"},
    // Positions are held to the world's bound, the guard's test, whatever the orientation: a box
    // at 7.8e16 m turned by 5 degrees loaded (its corners were apart in x) but its saved file did
    // not (unturned, its corners rounded onto each other).
    {"turned box beyond the bound",
     "<scene name='e'>\n<box pos='1 8 77777777777777705' euler='0 5 0'/>\n</scene>", 2, "pos",
     "beyond the world's bound of 1e+06 m"},
    {"box beyond the bound", "<scene name='e'>\n<box pos='0 0 1e17'/>\n</scene>", 2, "pos",
     "beyond the world's bound"},
    {"particle beyond a small bound",
     "<scene name='e'>\n<world bound='10'/>\n<particle pos='0 11 0'/>\n</scene>", 3, "pos",
     "beyond the world's bound of 10 m"},
    // The ground too, whichever of <ground> and <world> comes first.
    {"ground beyond a small bound", "<scene name='e'>\n<ground height='-11'/>\n<world bound='10'/>\n</scene>",
     2, "height", "puts the ground beyond the world's bound of 10 m"},
    // Every digit of where it reaches: 999999.9 + 0.5 read "1e+06", as if on the bound.
    {"box whose corner just crosses the bound", "<scene name='e'>\n<box pos='0 999999.9 0'/>\n</scene>", 2,
     "", "reaches (-0.5, 1000000.4, -0.5), beyond the world's bound of 1e+06 m"},
    {"stack that grows beyond the bound",
     "<scene name='e'>\n<world bound='10'/>\n<stack pos='0 0 0' count='20'/>\n</scene>", 3, "",
     "reaches (-0.5, 11, -0.5), beyond the world's bound of 10 m"},
    // A rigid body has no particles: its centre is what the bound holds (the writer refused such a
    // world after it loaded, found by the scene fuzzer).
    {"rigid stack that grows beyond the bound",
     "<scene name='e'>\n<world bound='10'/>\n<stack pos='0 0 0' count='20' model='rigid'/>\n</scene>", 3, "",
     "reaches (0, 10.5, 0), beyond the world's bound of 10 m"},
    // Sizes a generator makes are held to a body's, as a <box>'s are: a pyramid tapering below
    // 1 mm loaded and its file did not; a side of 1e200 m made corners no double tells apart and
    // a message ("addBody: centre or size too large") that named no attribute.
    {"pyramid that tapers below the smallest size",
     "<scene name='e'>\n<pyramid pos='0 0 0' base='3' taper='1e-3'/>\n</scene>", 2, "taper",
     "'0.001' makes the top row's boxes 1e-06 m, below the smallest size of 0.001 m"},
    {"box larger than any world", "<scene name='e'>\n<box pos='0 0 0' size='1e200'/>\n</scene>", 2, "size",
     "sizes must be from 0.001 to 2e+09 (m)"},
    {"capsule longer than any world",
     "<scene name='e'>\n<capsule pos='0 0 0' radius='0.1' length='1e200'/>\n</scene>", 2, "length",
     "must be at most 2e+09 (m)"},
    {"grid spaced wider than any world",
     "<scene name='e'>\n<grid pos='0 0 0' count='2 1 1' spacing='1e200'/>\n</scene>", 2, "spacing",
     "must be > 0 and at most 2e+09 (m)"},
    {"link point beyond the bound",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/><box name='b' pos='2 0 0'/>\n"
     "<link a='a' b='b' point='1 0 1e12'/>\n</scene>",
     3, "point", "beyond the world's bound"},
    {"bound too large", "<scene name='s'>\n<world bound='1e10'/>\n</scene>", 2, "bound", "at most 1e+09 (m)"},
    {"camera beyond the bound", "<scene name='s'>\n<camera eye='0 0 1e39'/>\n</scene>", 2, "eye",
     "within the world's bound of 1e+06 m"},
    {"declared UTF-16", "<?xml version='1.0' encoding='UTF-16'?>\n<scene name='s'/>", 1, "encoding",
     "'UTF-16' is not supported; scene files are UTF-8"},
    {"count above the limit", "<scene name='s'>\n<stack pos='0 0 0' count='1001'/>\n</scene>", 2, "count",
     "from 1 to 1000"},
    {"grid too large", "<scene name='s'>\n<grid pos='0 0 0' count='100 100 100'/>\n</scene>", 2, "count",
     "more than 100000"},
    {"bad model", "<scene name='s'>\n<box pos='0 0 0' model='sphere'/>\n</scene>", 2, "model",
     "corners, tetra or rigid"},
    {"model on a particle", "<scene name='s'>\n<particle pos='0 1 0' model='rigid'/>\n</scene>", 2, "model",
     "a loose particle has no model"},
    {"joint of a rigid body to itself",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<link a='a' b='a' point='0 1.5 "
     "0'/>\n</scene>",
     3, "b", "must name a different body from a"},
    {"joint on a particle body",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<box name='b' pos='0 2 0'/>\n"
     "<joint type='hinge' a='a' b='b' pivot='0 1.5 0' axis='1 0 0' reference='0 -1 0' min='-10' "
     "max='10'/>\n</scene>",
     4, "b", "a <joint> joins rigid bodies"},
    {"joint reference along its axis",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<box name='b' pos='0 2 0' "
     "model='rigid'/>\n"
     "<joint type='cone' a='a' b='b' pivot='0 1.5 0' axis='0 1 0' reference='0 2 0' swing='30'/>\n</scene>",
     4, "reference", "must not lie along axis"},
    {"joint axis whose length overflows",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<box name='b' pos='0 2 0' "
     "model='rigid'/>\n"
     "<joint type='hinge' a='a' b='b' pivot='0 1.5 0' axis='1e200 0 0' reference='0 -1 0' min='-10' "
     "max='10'/>\n</scene>",
     4, "axis", "must be non-zero and of finite length (is 1e+200 0 0)"},
    {"drive strength above 1",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<box name='b' pos='0 2 0' "
     "model='rigid'/>\n"
     "<joint type='cone' a='a' b='b' pivot='0 1.5 0' axis='0 1 0' reference='1 0 0' swing='30' "
     "strength='1.5'/>\n</scene>",
     4, "strength", "'1.5' must be from 0 to 1"},
    {"drive stiffness of 0",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<box name='b' pos='0 2 0' "
     "model='rigid'/>\n"
     "<joint type='cone' a='a' b='b' pivot='0 1.5 0' axis='0 1 0' reference='1 0 0' swing='30' "
     "drive-stiffness='0'/>\n</scene>",
     4, "drive-stiffness", "'0' must be > 0 (N m/rad)"},
    {"drive target not three angles",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<box name='b' pos='0 2 0' "
     "model='rigid'/>\n"
     "<joint type='cone' a='a' b='b' pivot='0 1.5 0' axis='0 1 0' reference='1 0 0' swing='30' "
     "drive-target='10 20'/>\n</scene>",
     4, "drive-target", "'10 20' must be three finite numbers (degrees)"},
    {"particle joint on a rigid body",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<box name='b' pos='0 2 0'/>\n"
     "<particle-joint a='a' b='b' pivot='0 1.5 0'/>\n</scene>",
     4, "a", "names a rigid body; a <particle-joint> joins particle bodies"},
    {"particle joint of one body",
     "<scene name='s'>\n<box name='a' pos='0 1 0'/>\n<particle-joint a='a' b='a' pivot='0 1.5 0'/>\n</scene>",
     3, "b", "must name a different body from a"},
    {"particle joint without its pivot",
     "<scene name='s'>\n<box name='a' pos='0 1 0'/>\n<box name='b' pos='0 2 0'/>\n"
     "<particle-joint a='a' b='b' strength='0.5'/>\n</scene>",
     4, "pivot", "is required"},
    {"particle joint's drive too strong",
     "<scene name='s'>\n<box name='a' pos='0 1 0'/>\n<box name='b' pos='0 2 0'/>\n"
     "<particle-joint a='a' b='b' pivot='0 1.5 0' strength='2'/>\n</scene>",
     4, "strength", "must be"},
    {"body drive without its strength",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<body-drive body='a'/>\n</scene>", 3,
     "strength", "is required"},
    {"body drive of no stiffness",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<body-drive body='a' strength='1'\n "
     "angular-stiffness='-2'/>\n</scene>",
     4, "angular-stiffness", "'-2' must be > 0 (N m/rad)"},
    {"hinge stops crossed",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<box name='b' pos='0 2 0' "
     "model='rigid'/>\n"
     "<joint type='hinge' a='a' b='b' pivot='0 1.5 0' axis='1 0 0' reference='0 -1 0' min='20' "
     "max='10'/>\n</scene>",
     4, "max", "must be >= min"},
    {"joint friction on a rigid body",
     "<scene name='s'>\n<box name='a' pos='0 1 0'/>\n<box name='b' pos='0 2 0' model='rigid'/>\n"
     "<joint-friction a='a' b='b' damping='2'/>\n</scene>",
     4, "b", "a <joint-friction> joins particle bodies"},
    {"joint friction of a body with itself",
     "<scene name='s'>\n<box name='a' pos='0 1 0'/>\n<joint-friction a='a' b='a' damping='2'/>\n</scene>", 3,
     "b", "must name a different body from a"},
    {"negative joint friction",
     "<scene name='s'>\n<box name='a' pos='0 1 0'/>\n<box name='b' pos='0 2 0'/>\n"
     "<joint-friction a='a' b='b' damping='-1'/>\n</scene>",
     4, "damping", "must be >= 0 (1/s)"},
    {"joint friction without its rate",
     "<scene name='s'>\n<box name='a' pos='0 1 0'/>\n<box name='b' pos='0 2 0'/>\n"
     "<joint-friction a='a' b='b'/>\n</scene>",
     4, "damping", "is required"},
    {"bad method", "<scene name='s'>\n<solver method='magic'/>\n</scene>", 2, "method", "gauss-seidel"},
    {"zero iterations", "<scene name='s'>\n<solver iterations='0'/>\n</scene>", 2, "iterations",
     "from 1 to 1000"},
    {"not XML", "<scene name='s'>\n<box pos='0 0 0'>\n</scene>", 3, "", "not well-formed XML"},
    {"wrong root", "<world/>", 1, "", "root element must be <scene>"},
    {"scene without a name", "<scene>\n</scene>", 1, "name", "is required"},
    {"duplicate name", "<scene name='s'>\n<box name='a' pos='0 0 0'/>\n<box name='a' pos='0 2 0'/>\n</scene>",
     3, "name", "already the name"},
    {"generator name clash",
     "<scene name='s'>\n<box name='stack[1]' pos='9 0 0'/>\n<stack pos='0 0 0' count='3'/>\n</scene>", 3,
     "name", "already the name"},
    {"stick to a missing particle",
     "<scene name='s'>\n<particle name='a' pos='0 0 0'/>\n<stick a='a' b='zz'/>\n</scene>", 3, "b",
     "'zz' is not the name of a particle"},
    {"stick to a box",
     "<scene name='s'>\n<particle name='a' pos='0 0 0'/>\n<box name='b' pos='1 0 0'/>\n<stick a='a' "
     "b='b'/>\n</scene>",
     4, "b", "not the name of a particle"},
    {"length and min together",
     "<scene name='s'>\n<particle name='a' pos='0 0 0'/><particle name='b' pos='1 0 0'/>\n<stick a='a' b='b' "
     "length='1' min='0.5'/>\n</scene>",
     3, "length", "not both"},
    {"min above max",
     "<scene name='s'>\n<particle name='a' pos='0 0 0'/><particle name='b' pos='1 0 0'/>\n<stick a='a' b='b' "
     "min='2' max='1'/>\n</scene>",
     3, "max", ">= min"},
    {"bad ragdoll model", "<scene name='s'>\n<ragdoll pos='0 1 0'\n model='puppet'/>\n</scene>", 3, "model",
     "seed, lean or rigid"},
    {"zero ragdoll scale", "<scene name='s'>\n<ragdoll pos='0 1 0' scale='0'/>\n</scene>", 2, "scale",
     "'0' must be from 0.02 to 1000"},
    {"ragdoll part name clash",
     "<scene name='s'>\n<box name='r.head' pos='5 0 0'/>\n<ragdoll name='r' pos='0 1 0'/>\n</scene>", 3,
     "name", "already"},
    {"body damping above 1", "<scene name='s'>\n<solver body-damping='1.5'/>\n</scene>", 2, "body-damping",
     "from 0 to 1"},
    {"keep-spin not on or off", "<scene name='s'>\n<solver keep-spin='yes'/>\n</scene>", 2, "keep-spin",
     "'yes' must be on or off"},
    {"settings twice", "<scene name='s'>\n<world/>\n<world/>\n</scene>", 3, "", "more than once"},
    {"text in an element", "<scene name='s'>\n<box pos='0 0 0'>big</box>\n</scene>", 2, "", "no child"},
    {"bad boolean", "<scene name='s'>\n<particle pos='0 0 0' pinned='yes'/>\n</scene>", 2, "pinned",
     "true or false"},
    {"zero ground normal", "<scene name='s'>\n<ground normal='0 0 0'/>\n</scene>", 2, "normal", "non-zero"},
    {"overflowing ground normal", "<scene name='s'>\n<ground normal='1e300 1e300 0'/>\n</scene>", 2, "normal",
     "finite length"},
    // A chain's direction is normalised as the ground's normal is: its length overflowed to inf,
    // the direction became 0 and every particle was put at pos without a word.
    {"overflowing chain direction",
     "<scene name='s'>\n<chain pos='0 1 0' links='3' length='1'\n direction='1e308 1e308 0'/>\n</scene>", 3,
     "direction", "must be non-zero and of finite length"},
    {"zero chain direction",
     "<scene name='s'>\n<chain pos='0 1 0' links='3' length='1' direction='0 0 0'/>\n</scene>", 2,
     "direction", "non-zero"},
    {"element after the root", "<scene name='s'>\n</scene>\n<box pos='0 5 0'/>", 3, "", "nothing may follow"},
    {"text after the root", "<scene name='s'>\n</scene>\n\n  junk\n", 4, "", "nothing may follow"},
    {"attribute twice", "<scene name='s'>\n<box pos='0 1 0'\n pos='0 50 0'/>\n</scene>", 3, "pos",
     "given twice"},
    // <expect> keeps its attributes as written, so no rejectUnknownAttributes saw a doubled one: the lab
    // read the first kind, and the stability suite passed over kind="position" kind="pass".
    {"expect attribute twice",
     "<scene name='s'>\n<particle name='p' pos='0 1 0'/>\n<expect kind='position'\n kind='pass' body='p' "
     "at='1' pos='0 1 0'/>\n</scene>",
     4, "kind", "given twice"},
    // A body has one drive: a second <body-drive> replaced the first without a word.
    {"second body drive",
     "<scene name='s'>\n<box name='a' pos='0 1 0' model='rigid'/>\n<body-drive body='a' strength='1'/>\n"
     "<body-drive body='a' strength='0.5'/>\n</scene>",
     4, "body", "'a' already has a <body-drive>, on line 3"},
    {"text inside scene", "<scene name='s'>\n<world/>\n  stray words\n</scene>", 3, "",
     "text: unexpected text"},
    {"dt too small", "<scene name='s'>\n<solver dt='1e-200'/>\n</scene>", 2, "dt", "from 1e-06 to 1"},
    {"compliance too large",
     "<scene name='s'>\n<particle name='a' pos='0 0 0'/><particle name='b' pos='1 0 0'/>\n<stick a='a' b='b' "
     "compliance='1e300'/>\n</scene>",
     3, "compliance", "from 0 to 1e+06"},
    {"restitution above 1", "<scene name='s'>\n<solver\n restitution='1.5'/>\n</scene>", 3, "restitution",
     "from 0 to 1"},
    {"negative solver compliance", "<scene name='s'>\n<solver compliance='-1'/>\n</scene>", 2, "compliance",
     "from 0 to 1e+06"},
    {"link to an unknown box",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/>\n<link a='a'\n b='zz' point='0 0 0'/>\n</scene>", 4, "b",
     "'zz' is not the name of a box, capsule or particle defined above"},
    {"link above its box",
     "<scene name='s'>\n<link a='a' b='b' point='0 0 0'/>\n<box name='a' pos='0 0 0'/><box name='b' pos='2 0 "
     "0'/>\n"
     "</scene>",
     2, "a", "defined above"},
    {"link from a box to itself",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/>\n<link a='a' b='a' point='0 0 0'/>\n</scene>", 3, "b",
     "different body"},
    {"link with point and a-point",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/><box name='b' pos='2 0 0'/>\n"
     "<link a='a' b='b' point='1 0 0'\n a-point='0 0 0' b-point='2 0 0'/>\n</scene>",
     4, "a-point", "not both"},
    {"link without a point",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/><box name='b' pos='2 0 0'/>\n<link a='a' "
     "b='b'/>\n</scene>",
     3, "point", "is required"},
    {"link with a-point alone",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/><box name='b' pos='2 0 0'/>\n"
     "<link a='a' b='b' a-point='0 0 0'/>\n</scene>",
     3, "b-point", "is required with a-point"},
    {"link max of zero",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/><box name='b' pos='2 0 0'/>\n"
     "<link a='a' b='b' point='1 0 0' max='0'/>\n</scene>",
     3, "max", "> 0"},
    {"link min above max",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/><box name='b' pos='2 0 0'/>\n"
     "<link a='a' b='b' a-point='0 0 0' b-point='2 0 0' min='2'\n max='1'/>\n</scene>",
     4, "max", ">= min"},
    {"link negative min",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/><box name='b' pos='2 0 0'/>\n"
     "<link a='a' b='b' point='1 0 0' min='-1'/>\n</scene>",
     3, "min", ">= 0"},
    {"no-collision of a box with itself",
     "<scene name='s'>\n<box name='a' pos='0 0 0'/>\n<no-collision a='a'\n b='a'/>\n</scene>", 4, "b",
     "different box"},
    {"no-collision with a particle",
     "<scene name='s'>\n<particle name='p' pos='0 0 0'/><box name='a' pos='0 0 0'/>\n"
     "<no-collision a='p' b='a'/>\n</scene>",
     3, "a", "'p' is not the name of a box or capsule defined above"},
    {"collision group too large", "<scene name='s'>\n<box pos='0 0 0' group='4294967296'/>\n</scene>", 2,
     "group", "from 0 to 4294967295"},
};

TEST(SceneErrors, EachNamesFileLineAndAttribute) {
  for (const BadScene& c : kCases) testing_scenes::expectRefused(c);
}

// Rigid bodies have no particles, so the particle limit let through ten grids of 100,000 rigid
// boxes, which took 17.6 GB in their first step: the grid that passes 250,000 bodies is named.
TEST(SceneErrors, TooManyBodiesAreRefusedAtTheElementThatPassesTheLimit) {
  testing_scenes::expectRefused({"250,000 bodies",
                                 "<scene name='s'>\n"
                                 "<grid name='a' pos='0 0 0' count='100 10 100' model='rigid'/>\n"
                                 "<grid name='b' pos='300 0 0' count='100 10 100' model='rigid'/>\n"
                                 "<grid name='c' pos='600 0 0' count='100 10 100' model='rigid'/>\n</scene>",
                                 4, "", "the scene has more than 250000 bodies"});
}

// Each <expect> keeps its attributes as strings, some 20 times their bytes in the file: a file of a
// million took gigabytes. The one past the limit is named.
TEST(SceneErrors, TooManyExpectationsAreRefusedAtTheFirstPastTheLimit) {
  std::string xml = "<scene name='s'>\n";
  for (int i = 0; i < 1001; ++i) xml += "<expect kind='pass' metric='speed' max='1' over='0 1'/>\n";
  testing_scenes::expectRefused({"1001 expects", (xml + "</scene>").c_str(), 1002, "",
                                 "<expect>: the scene has more than 1000 <expect> elements"});
  const std::size_t end = xml.rfind("<expect");
  EXPECT_EQ(scenes::loadSceneText(xml.substr(0, end) + "</scene>", "s.xml").expectations.size(), 1000u);
}

// Each element that adds a constraint was held by nothing but the file's size: 512 MiB of
// <no-collision> or <joint> elements between two boxes. They are held together to kMaxConstraints,
// refused at the one past it; the limit is given small here, so as not to write millions.
TEST(SceneErrors, TooManyConstraintsAreRefusedAtTheFirstPastTheLimit) {
  const std::string bodies =
      "<scene name='s'>\n<particle name='p' pos='0 1 0'/>\n<particle name='q' pos='0 2 0'/>\n"
      "<box name='a' pos='0 5 0' model='rigid'/>\n<box name='b' pos='2 5 0' model='rigid'/>\n"
      "<box name='c' pos='0 9 0'/>\n<box name='d' pos='2 9 0'/>\n";  // lines 1 to 7
  const std::string constraints[] = {
      "<stick a='p' b='q'/>",
      "<link a='a' b='b' point='1 5 0'/>",
      "<joint type='cone' a='a' b='b' pivot='1 5 0' axis='1 0 0' reference='0 1 0' swing='30'/>",
      "<particle-joint a='c' b='d' pivot='1 9 0'/>",
      "<joint-friction a='c' b='d' damping='2'/>",
      "<no-collision a='a' b='b'/>"};
  const std::string says =
      "the scene has more than 3 constraints (<stick>, <link>, <joint>, <particle-joint>, "
      "<joint-friction> and <no-collision> elements)";
  auto refusedAt = [&](const std::string& xml) {
    try {
      (void)scenes::detail::loadSceneText(xml, "s.xml", {.constraints = 3});
    } catch (const scenes::LoadError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
      return e.line();
    }
    return 0;
  };
  for (const std::string& constraint : constraints) {
    SCOPED_TRACE(constraint);
    std::string xml = bodies;
    for (int i = 0; i < 4; ++i) xml += constraint + "\n";
    EXPECT_EQ(refusedAt(xml + "</scene>"), 11);
    const std::size_t last = xml.rfind(constraint);
    EXPECT_EQ(refusedAt(xml.substr(0, last) + "</scene>"), 0);
  }
  // All kinds count together: the fourth is refused, whatever the first three were.
  std::string mixed = bodies;
  for (const std::string& constraint : constraints) mixed += constraint + "\n";
  EXPECT_EQ(refusedAt(mixed + "</scene>"), 11);
  // Under the loader's own limit the scene holds them all.
  const scenes::Scene all = scenes::loadSceneText(mixed + "</scene>", "s.xml");
  EXPECT_EQ(all.world.rigidJoints().size(), 1u);
  EXPECT_EQ(all.world.particleJoints().size(), 1u);
  EXPECT_EQ(all.world.jointFrictions().size(), 1u);
}

// A file written body by body (a recording's part scene) never holds a generator: under
// LoadOptions::bodyByBody each is refused at its line, before the first body of the file is built,
// and the same text loads without the option.
TEST(SceneErrors, AGeneratorInAFileWrittenBodyByBodyIsRefusedAtItsLine) {
  scenes::LoadOptions bodyByBody;
  bodyByBody.bodyByBody = true;
  const std::string boxOnly = "<scene name='s'>\n<box name='b' pos='0 3 0'/>\n</scene>";
  const phys::World oneBox = scenes::loadSceneText(boxOnly, "s.xml", bodyByBody).world;
  EXPECT_EQ(oneBox.bodies().size(), 1u);
  for (const std::string element :
       {"<stack name='s' pos='0 0.5 0' count='3'/>", "<pyramid name='p' pos='0 0.5 0' base='3'/>",
        "<grid name='g' pos='0 0.5 0' count='2 2 2'/>",
        "<chain name='c' pos='0 2 0' links='3' length='0.1'/>", "<ragdoll name='r' pos='0 1 0'/>"}) {
    const std::string kind = element.substr(1, element.find(' ') - 1);
    SCOPED_TRACE(kind);
    const std::string xml = "<scene name='s'>\n<box name='b' pos='0 3 0'/>\n" + element + "\n</scene>";
    EXPECT_GT(scenes::loadSceneText(xml, "s.xml").world.particles().size(), oneBox.particles().size());
    try {
      (void)scenes::loadSceneText(xml, "s.xml", bodyByBody);
      ADD_FAILURE() << "loaded";
    } catch (const scenes::LoadError& e) {
      EXPECT_EQ(e.line(), 3);
      EXPECT_NE(std::string(e.what()).find("s.xml:3: <" + kind + ">: makes many bodies from one line"),
                std::string::npos)
          << e.what();
    }
  }
}

// A description is one line; XML makes a line break of &#10; or &#13; only (a typed one is read as
// a space, and loads).
TEST(SceneErrors, ADescriptionOfTwoLinesIsRefused) {
  for (const char* lineBreak : {"&#10;", "&#13;", "&#xA;"}) {
    testing_scenes::expectRefused(
        {lineBreak, (std::string("<scene name='s'\n description='a") + lineBreak + "b'>\n</scene>").c_str(),
         2, "description", "holds a line break (&#10; or &#13;); a description is one line"});
  }
  EXPECT_EQ(scenes::loadSceneText("<scene name='s' description='a\nb\tc'/>", "s.xml").description, "a b c");
}

// What loadSceneFile says, or "" when it loaded.
std::string fileError(const std::filesystem::path& file) {
  try {
    scenes::loadSceneFile(file);
  } catch (const scenes::LoadError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("not a LoadError: ") + e.what();
  }
  return {};
}

TEST(SceneErrors, MissingFileIsNamedWithTheOsReason) {
  EXPECT_EQ(fileError("/nonexistent/scene.xml"),
            "/nonexistent/scene.xml: cannot open: No such file or directory");
}

// A folder gave libstdc++'s "basic_filebuf::underflow" with no path, from an exception that was
// not a LoadError.
TEST(SceneErrors, AFolderIsNamedAsSuch) {
  const testing_app::TempFolder folder;
  EXPECT_EQ(fileError(folder.path), folder.path.string() + ": is a folder, not a file");
}

TEST(SceneErrors, AnUnreadableFileGivesTheOsReason) {
  const testing_app::TempFolder folder;
  const std::filesystem::path file = folder.path / "secret.xml";
  std::ofstream(file) << "<scene name='s'/>";
  std::filesystem::permissions(file, std::filesystem::perms::owner_read);
  std::filesystem::permissions(folder.path, std::filesystem::perms::owner_all |
                                                std::filesystem::perms::others_read |
                                                std::filesystem::perms::others_exec);
  EXPECT_EQ(testing_app::runAsNobody([&] { return fileError(file); }),
            file.string() + ": cannot open: Permission denied");
}

// /dev/zero was read until memory ran out.
TEST(SceneErrors, AnEndlessDeviceIsCutOff) {
  EXPECT_NE(fileError("/dev/zero").find("/dev/zero: is larger than"), std::string::npos);
}

// Text handed in whole is held to the limit a file is read to. The limit is given small here so
// as not to hold 512 MiB; the public loadSceneText gives kMaxSceneBytes, which this does not run.
TEST(SceneErrors, TextOverTheLimitIsRefusedAsAWhole) {
  const std::string xml = "<scene name='s'/>";
  try {
    scenes::detail::loadSceneText(xml, "big.xml", {.bytes = xml.size() - 1});
    ADD_FAILURE() << "loaded";
  } catch (const scenes::LoadError& e) {
    EXPECT_EQ(std::string(e.what()), "big.xml: is larger than 16 bytes, the most that is read");
    EXPECT_EQ(e.line(), 0);
  }
  EXPECT_EQ(scenes::detail::loadSceneText(xml, "fits.xml", {.bytes = xml.size()}).name, "s");
}

// UTF-16 and UTF-32 files got pugixml's "Could not determine tag type".
TEST(SceneErrors, OtherEncodingsAreNamed) {
  const testing_app::TempFolder folder;
  const std::string ascii = "<scene name='s'/>";
  auto widen = [&](int width, bool big, bool mark) {
    std::string out;
    auto put = [&](char32_t c) {
      for (int i = 0; i < width; ++i) {
        const int shift = 8 * (big ? width - 1 - i : i);
        out.push_back(static_cast<char>((c >> shift) & 0xff));
      }
    };
    if (mark) put(0xFEFF);
    for (char c : ascii) put(static_cast<unsigned char>(c));
    return out;
  };
  const struct {
    int width;
    bool big, mark;
    const char* says;
  } cases[] = {{2, false, true, "UTF-16 (little-endian)"},  {2, true, true, "UTF-16 (big-endian)"},
               {2, false, false, "UTF-16 (little-endian)"}, {2, true, false, "UTF-16 (big-endian)"},
               {4, false, true, "UTF-32 (little-endian)"},  {4, true, true, "UTF-32 (big-endian)"},
               {4, false, false, "UTF-32 (little-endian)"}, {4, true, false, "UTF-32 (big-endian)"}};
  for (const auto& c : cases) {
    const std::filesystem::path file = folder.path / "wide.xml";
    std::ofstream(file, std::ios::binary) << widen(c.width, c.big, c.mark);
    EXPECT_EQ(fileError(file),
              file.string() + ":1: the file is " + c.says + "; scene files are UTF-8 (save it as UTF-8)");
  }
  // A UTF-8 byte order mark is fine.
  std::ofstream(folder.path / "bom.xml", std::ios::binary) << "\xEF\xBB\xBF" << ascii;
  EXPECT_EQ(fileError(folder.path / "bom.xml"), "");
}

TEST(SceneErrors, AZeroByteIsNamedWithItsLine) {
  const std::string text = std::string("<scene name='s'>\n<box pos='0 1 0'/>\n") + '\0' + "</scene>";
  try {
    scenes::loadSceneText(text, "nul.xml");
    FAIL();
  } catch (const scenes::LoadError& e) {
    EXPECT_EQ(std::string(e.what()), "nul.xml:3: a zero byte: this is not a text file");
  }
}

// Bytes that are not UTF-8 (a name saved as Latin-1, say) are named with their line: pugixml
// would pass them through to the sandbox's labels and the lab's CSVs. Every form UTF-8 forbids is
// refused (RFC 3629), and every character it allows loads, up to U+10FFFF.
TEST(SceneErrors, BytesThatAreNotUtf8AreNamedWithTheirLine) {
  auto load = [](const std::string& name) {
    try {
      scenes::loadSceneText("<scene name='s'>\n<box name='" + name + "' pos='0 1 0'/>\n</scene>", "n.xml");
      return std::string();
    } catch (const scenes::LoadError& e) {
      return std::string(e.what());
    }
  };
  const struct {
    const char* bytes;
    const char* says;
  } bad[] = {{"M\xFCller", "byte 0xFC is"},                // Latin-1's u with umlaut
             {"a\x80", "byte 0x80 is"},                    // a continuation byte alone
             {"\xC0\xAF", "byte 0xC0 is"},                 // '/' in an overlong form
             {"\xE0\x80\xAF", "bytes 0xE0 0x80 are"},      // the same in three bytes
             {"\xED\xA0\x80", "bytes 0xED 0xA0 are"},      // a surrogate, U+D800
             {"\xF4\x90\x80\x80", "bytes 0xF4 0x90 are"},  // U+110000, past the last code point
             {"\xE2\x82", "bytes 0xE2 0x82 0x27 are"}};    // a character cut short by the quote
  for (const auto& b : bad) {
    EXPECT_EQ(load(b.bytes),
              std::string("n.xml:2: ") + b.says + " not UTF-8; scene files are UTF-8 (save it as UTF-8)")
        << b.bytes;
  }
  // A file that says it is Latin-1 is told so (the declaration is read first); bytes that are
  // not UTF-8 before the XML breaks are named before the XML error.
  auto loadText = [](const std::string& text) {
    try {
      scenes::loadSceneText(text, "n.xml");
      return std::string();
    } catch (const scenes::LoadError& e) {
      return std::string(e.what());
    }
  };
  const std::string latin = "<?xml version='1.0' encoding='ISO-8859-1'?>\n<scene name='M\xFCller'/>\n";
  EXPECT_NE(loadText(latin).find("'ISO-8859-1' is not supported"), std::string::npos) << loadText(latin);
  EXPECT_EQ(loadText("<scene name='s'>\n<box name='\xFC'/>\n<box"),
            "n.xml:2: byte 0xFC is not UTF-8; scene files are UTF-8 (save it as UTF-8)");
  // At the very end of the file, cut short by it.
  EXPECT_EQ(loadText("<scene name='s'/>\n<!-- -->\xE2\x82"),
            "n.xml:2: bytes 0xE2 0x82 are not UTF-8; scene files are UTF-8 (save it as UTF-8)");
  for (const char* good :
       {"M\xC3\xBCller", "\xE2\x82\xAC", "\xED\x9F\xBF", "\xF0\x9F\xA6\xB4", "\xF4\x8F\xBF\xBF"}) {
    EXPECT_EQ(load(good), "") << good;  // u umlaut, the euro sign, U+D7FF, a bone emoji, U+10FFFF
  }
}

TEST(SceneErrors, GarbageNeverCrashes) {
  // Truncations of a valid scene at every byte: each loads or throws LoadError, nothing else.
  const std::string good =
      "<scene name='s'><world gravity='0 -9.81 0'/><ground/><box name='b' pos='0 1 0' size='1 2 3'/>"
      "<particle name='p' pos='0 3 0'/><particle name='q' pos='1 3 0'/><stick a='p' b='q'/>"
      "<chain pos='0 5 0' links='3' length='0.5'/></scene>";
  int loaded = 0;
  for (std::size_t n = 0; n <= good.size(); ++n) {
    try {
      scenes::loadSceneText(good.substr(0, n), "cut.xml");
      ++loaded;
    } catch (const scenes::LoadError&) {
    }
  }
  EXPECT_EQ(loaded, 1);  // only the whole text
}

// A message quotes what the file holds (a number, a name, a method, an attribute's or an element's
// name, a clip's path): a megabyte of it is cut, saying how much more there was, and the message
// still names the line and the attribute.
TEST(SceneErrors, AHugeValueIsCut) {
  const std::string huge(std::size_t{1} << 20, '9');
  const struct {
    std::string xml;
    const char* attribute;
    const char* starts;
  } cases[] = {
      {"<box pos='0 1 0'\n mass='" + huge + "'/>", "mass", "<box> attribute 'mass': '999"},
      {"<particle name='p' pos='0 1 0'/><particle name='q' pos='1 1 0'/>\n<stick a='p' b='" + huge + "'/>",
       "b", "<stick> attribute 'b': '999"},
      {"\n<solver method='" + huge + "'/>", "method", "<solver> attribute 'method': '999"},
      {"\n<character ragdoll='r' clip='" + huge + "'/>", "clip", "<character> attribute 'clip': "},
      {"\n<box pos='0 1 0' x" + huge + "='1'/>", "", "<box> attribute 'x999"},
      {"\n<box" + huge + "/>", "", "<box999"},
  };
  for (const auto& c : cases) {
    try {
      scenes::loadSceneText("<scene name='s'>\n" + c.xml + "\n</scene>", "huge.xml");
      ADD_FAILURE() << c.starts << ": loaded";
    } catch (const scenes::LoadError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(std::string("huge.xml:3: ") + c.starts, 0), 0u) << message.substr(0, 200);
      EXPECT_LT(message.size(), 1100u) << c.starts;
      EXPECT_NE(message.find(" more bytes)"), std::string::npos) << message.substr(0, 500);
      if (*c.attribute != '\0') {
        EXPECT_EQ(e.attribute(), c.attribute);
      }
      EXPECT_LT(e.attribute().size(), 1100u);
    }
  }
  // A message of the loader's own that is long, <character>'s list of known attributes, is whole.
  try {
    scenes::loadSceneText(
        "<scene name='s'>\n<ragdoll name='r' pos='0 1 0' model='rigid'/>\n<character "
        "ragdoll='r' clip='" DATA_DIR "/assets/clips/run.bvh'\n bogus='1'/>\n</scene>",
        "long.xml");
    ADD_FAILURE() << "loaded";
  } catch (const scenes::LoadError& e) {
    const std::string message = e.what();
    EXPECT_GT(message.size(), 420u);  // more than the 400 bytes a clip error keeps
    EXPECT_EQ(message.find("more bytes"), std::string::npos) << message;
    EXPECT_NE(message.find("held-turns)"), std::string::npos) << message;
  }
}

// pugixml takes a control character in an attribute, raw or as a reference, though XML allows
// none but tab, line feed and carriage return: a megabyte value that starts with a terminal's
// "clear screen" is refused naming the character, not quoted, and a name with a line feed loads.
TEST(SceneErrors, AControlCharacterInAValueIsRefused) {
  const std::string clear = "\x1b[2J" + std::string(std::size_t{1} << 20, '9');
  for (const std::string& value : {clear, std::string("a&#27;[2J"), std::string("a\x01")}) {
    for (const char* attribute : {"name", "mass"}) {
      try {
        scenes::loadSceneText(
            "<scene name='s'>\n<box pos='0 1 0'\n " + std::string(attribute) + "='" + value + "'/>\n</scene>",
            "c.xml");
        ADD_FAILURE() << attribute << ": loaded";
      } catch (const scenes::LoadError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind("c.xml:3: <box> attribute '" + std::string(attribute) +
                                    "': holds the control character 0x",
                                0),
                  0u)
            << message.substr(0, 200);
        EXPECT_EQ(e.attribute(), attribute);
        EXPECT_LT(message.size(), 200u);
      }
    }
  }
  // An <expect>'s values too, which the lab reads.
  testing_scenes::expectRefused({"expect",
                                 "<scene name='s'>\n<expect kind='pass'\n metric='a&#27;'/>\n</scene>", 3,
                                 "metric", "holds the control character 0x1B"});
  const scenes::Scene lines = scenes::loadSceneText(
      "<scene name='a&#10;b&#9;c&#13;'><box name='x&#10;y' pos='0 1 0'/></scene>", "lines.xml");
  EXPECT_EQ(lines.name, "a\nb\tc\r");
  EXPECT_EQ(lines.bodies.at(0).name, "x\ny");
}

// U+009B is xterm's one-character ESC [: a name holding "\u009B2J" loaded, and the lab's summary
// printed it to the terminal as it was. A C1 control is refused, as a byte or a reference, and a
// character just past them (U+00A0) is not.
TEST(SceneErrors, AC1ControlCharacterIsRefused) {
  testing_scenes::expectRefused({"C1 bytes",
                                 "<scene name='s'>\n<box pos='0 1 0'\n name='a\xC2\x9B"
                                 "2J'/>\n</scene>",
                                 3, "name", "holds the control character U+009B"});
  testing_scenes::expectRefused({"C1 reference",
                                 "<scene name='s'>\n<box pos='0 1 0' name='&#x85;'/>\n</scene>", 2, "name",
                                 "holds the control character U+0085"});
  testing_scenes::expectRefused({"C1 in the scene's name", "<scene name='&#128;'/>", 1, "name", "U+0080"});
  const scenes::Scene spaced =
      scenes::loadSceneText("<scene name='s'><box name='a&#xA0;b' pos='0 1 0'/></scene>", "ok.xml");
  EXPECT_EQ(spaced.bodies.at(0).name,
            "a\xC2\xA0"
            "b");
}

// A clip's bone names reach a message whole, from the clip's file rather than the scene's: a
// megabyte one that starts with "clear screen" is cut, its control byte shown as \x1b.
TEST(SceneErrors, AClipsBoneNameIsCutAndItsControlBytesShown) {
  const testing_app::TempFolder folder;
  const std::string bone = "\x1b[2J" + std::string(std::size_t{1} << 20, 'b');
  std::ofstream(folder.path / "odd.bvh")
      << "HIERARCHY\nROOT torso\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation "
         "Xrotation Yrotation\n JOINT "
      << bone
      << "\n {\n  OFFSET 0 1 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n  End Site\n  {\n   OFFSET 0 1 "
         "0\n "
         " }\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0 0 0 0 0 0 0\n";
  try {
    scenes::loadSceneText(
        "<scene name='s'>\n<ragdoll name='r' pos='0 1 0' model='rigid'/>\n<character "
        "ragdoll='r' clip='" +
            (folder.path / "odd.bvh").string() + "'/>\n</scene>",
        "bones.xml");
    ADD_FAILURE() << "loaded";
  } catch (const scenes::LoadError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("bones.xml:3: <character> attribute 'ragdoll': ", 0), 0u)
        << message.substr(0, 200);
    EXPECT_NE(message.find("'\\x1b[2Jbbb"), std::string::npos) << message.substr(0, 300);
    EXPECT_EQ(message.find('\x1b'), std::string::npos);
    EXPECT_LT(message.size(), 1100u);
    EXPECT_NE(message.find(" more bytes)"), std::string::npos);
  }
}

// then, get-up and from-clip name a clip as clip does, and an empty one is refused as clip's is
// (it read "attribute 'then': : no file name given").
TEST(SceneErrors, AnEmptyClipNameIsRefusedLikeClips) {
  const std::string ragdoll = "<scene name='s'>\n<ragdoll name='r' pos='0 1 0' model='rigid'/>\n";
  const std::string character = "<character ragdoll='r' clip='" DATA_DIR "/assets/clips/run.bvh'\n ";
  for (const std::string attribute : {"clip", "then", "get-up", "from-clip"}) {
    const std::string own = attribute == "clip" ? "<character ragdoll='r'\n " : character;
    const std::string more = attribute == "from-clip" ? " blend='0.5'" : "";
    testing_scenes::expectRefused({attribute.c_str(),
                                   (ragdoll + own + attribute + "=''" + more + "/>\n</scene>").c_str(), 4,
                                   attribute.c_str(), "must not be empty"});
  }
}

// A character's clip frame is a position like any the file places: from 1e300 m its root's drive
// flung the ragdoll out on the first step, for the guard to freeze, and the world could not be saved.
TEST(SceneErrors, ACharactersOriginIsHeldToTheBound) {
  const std::string scene =
      "<scene name='s'>\n<world bound='100'/><ragdoll name='r' pos='0 1 0' model='rigid'/>\n"
      "<character ragdoll='r' clip='" DATA_DIR "/assets/clips/run.bvh' root-strength='1'\n ";
  testing_scenes::expectRefused({"far origin", (scene + "origin='0 0 101'/>\n</scene>").c_str(), 4, "origin",
                                 "must be within the world's bound of 100 m along each axis"});
  EXPECT_NO_THROW(scenes::loadSceneText(scene + "origin='0 0 99'/>\n</scene>", "near.xml"));
}

// A joint's axis and reference were handed to World::addJoint unchecked, whose refusal named no
// attribute ("<joint>: addJoint: the axis must not be zero"), and said "the axis" of a zero b-axis.
TEST(SceneErrors, AJointsAxisOrReferenceIsRefusedByItsAttribute) {
  const std::string bodies =
      "<scene name='s'>\n<box name='u' pos='0 1.5 0' size='0.1 0.6 0.1' model='rigid'/>\n"
      "<box name='l' pos='0 0.9 0' size='0.1 0.6 0.1' model='rigid'/>\n"
      "<joint type='hinge' a='u' b='l' pivot='0 1.2 0' min='-90' max='0'\n ";
  const auto refused = [&](const char* what, const std::string& frame, const char* attribute,
                           const char* says) {
    testing_scenes::expectRefused({what, (bodies + frame + "/>\n</scene>").c_str(), 5, attribute, says});
  };
  refused("zero axis", "axis='0 0 0' reference='0 -1 0'", "axis", "must be non-zero and of finite length");
  refused("overflowing axis", "axis='1e300 1e300 0' reference='0 -1 0'", "axis",
          "must be non-zero and of finite length");
  refused("reference along the axis", "axis='1 0 0' reference='-2 0 0'", "reference", "must not lie along");
  refused("zero b-axis", "axis='1 0 0' reference='0 -1 0' b-axis='0 0 0' b-reference='0 -1 0'", "b-axis",
          "must be non-zero and of finite length");
  refused("b-reference along the b-axis",
          "axis='1 0 0' reference='0 -1 0' b-axis='0 1 0' b-reference='0 3 0'", "b-reference",
          "must not lie along b-axis");
  EXPECT_NO_THROW(scenes::loadSceneText(bodies + "axis='1e-5 0 0' reference='0 -1 0'/>\n</scene>", "ok.xml"));
  // Both of length 0: World::addJoint's "the parent's frame", as leaving both out is.
  EXPECT_NO_THROW(scenes::loadSceneText(
      bodies + "axis='1 0 0' reference='0 -1 0' b-axis='0 0 0' b-reference='0 0 0'/>\n</scene>", "ok.xml"));
}

// The reader refuses a joint's frame by the rule World::addJoint holds (phys::jointFrameProblem), not
// by a copy of it: at the rule's edges (a length that underflows or overflows, a reference 1e-9
// across the axis) the file is refused exactly when the world refuses the joint, by the attribute.
TEST(SceneErrors, AJointFrameIsRefusedExactlyWhenTheWorldRefusesIt) {
  const std::string bodies =
      "<scene name='s'>\n<box name='u' pos='0 1.5 0' size='0.1 0.6 0.1' model='rigid'/>\n"
      "<box name='l' pos='0 0.9 0' size='0.1 0.6 0.1' model='rigid'/>\n";
  const std::string joint = "<joint type='hinge' a='u' b='l' pivot='0 1.2 0' min='-90' max='0'\n ";
  const std::pair<phys::Vec3, phys::Vec3> frames[] = {
      {{1e-300, 0, 0}, {0, -1, 0}},   {{1e-160, 0, 0}, {0, -1, 0}}, {{1e154, 1e154, 0}, {0, 0, 1}},
      {{1e155, 1e155, 0}, {0, 0, 1}}, {{1, 0, 0}, {1, 1e-9, 0}},    {{1, 0, 0}, {1, 2e-9, 0}},
      {{0, 1, 0}, {1e300, 0, 1e300}}, {{0, 1, 0}, {1e150, 0, 0}},   {{1, 0, 0}, {0, -1, 0}}};
  const auto text = [](const phys::Vec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << v.x << " " << v.y << " " << v.z;
    return s.str();
  };
  for (const auto& [axis, reference] : frames) {
    SCOPED_TRACE(text(axis) + " / " + text(reference));
    const phys::JointFrameProblem problem = phys::jointFrameProblem(axis, reference);
    const std::string file =
        bodies + joint + "axis='" + text(axis) + "' reference='" + text(reference) + "'/>\n</scene>";
    scenes::Scene world = scenes::loadSceneText(bodies + "</scene>", "bodies.xml");
    phys::JointDesc d;
    d.a = phys::BodyId{0};
    d.b = phys::BodyId{1};
    d.pivot = {0, 1.2, 0};
    d.axis = axis;
    d.reference = reference;
    if (problem == phys::JointFrameProblem::None) {
      EXPECT_NO_THROW(scenes::loadSceneText(file, "s.xml"));
      EXPECT_NO_THROW(world.world.addJoint(d));
      continue;
    }
    const char* attribute = problem == phys::JointFrameProblem::Axis ? "axis" : "reference";
    testing_scenes::expectRefused({"frame", file.c_str(), 5, attribute, "must"});
    EXPECT_THROW(world.world.addJoint(d), std::invalid_argument);
  }
}

// A fade's shift and held root move the path the root's drive pulls along, as the origin does: a
// from-shift of 1e308 made every part's pose NaN on the first step, and 1e7 flung them out.
TEST(SceneErrors, ACharactersFadeShiftAndHeldRootAreHeldToTheBound) {
  const std::string scene =
      "<scene name='s'>\n<world bound='100'/><ragdoll name='r' pos='0 1 0' model='rigid'/>\n"
      "<character ragdoll='r' clip='" DATA_DIR "/assets/clips/run.bvh' root-strength='1' blend='0.5'\n ";
  const std::string from = "from-clip='" DATA_DIR "/assets/clips/run.bvh' ";
  std::string turns = "1 0 0 0";
  for (int bone = 1; bone < 10; ++bone) turns += ", 1 0 0 0";
  const std::string held = "held-turns='" + turns + "' ";
  testing_scenes::expectRefused({"far shift", (scene + from + "from-shift='1e308 0 0'/>\n</scene>").c_str(),
                                 4, "from-shift",
                                 "must be within the world's bound of 100 m along each axis"});
  testing_scenes::expectRefused({"far held root", (scene + held + "held-root='0 -101 0'/>\n</scene>").c_str(),
                                 4, "held-root",
                                 "must be within the world's bound of 100 m along each axis"});
  EXPECT_NO_THROW(scenes::loadSceneText(scene + from + "from-shift='99 0 -99'/>\n</scene>", "near.xml"));
  EXPECT_NO_THROW(scenes::loadSceneText(scene + held + "held-root='0 99 0'/>\n</scene>", "near.xml"));
}

}  // namespace

// pugixml decodes &#0; to a zero byte, which ended the value there (name='a&#0;b' loaded as "a"),
// and a surrogate or a code past U+10FFFF to bytes that are no UTF-8; XML forbids them all, so each
// is refused naming the attribute, or the text, holding it.
TEST(SceneErrors, ACharacterReferenceXmlForbidsIsRefusedNotCut) {
  for (const std::string reference :
       {"&#0;", "&#x0;", "&#x000;", "&#00;", "&#4294967296;", "&#x100000000;"}) {
    testing_scenes::expectRefused(
        {reference.c_str(),
         ("<scene name='s'>\n<box pos='0 1 0'\n name='a" + reference + "b'/>\n</scene>").c_str(), 3, "name",
         ("holds the character reference " + reference).c_str()});
  }
  testing_scenes::expectRefused(
      {"scene", "<scene\n name='a&#0;'>\n</scene>", 2, "name", "holds the character reference &#0;"});
  testing_scenes::expectRefused(
      {"text", "<scene name='s'>\n<box pos='0 1 0'>\nx&#0;</box>\n</scene>", 3, "", "(U+0000)"});
  // A surrogate, U+FFFE, U+FFFF and past U+10FFFF, which pugixml would make bytes that are no
  // UTF-8 (a world saved with them would not load again).
  for (const auto& [reference, named] :
       {std::pair{"&#xD800;", "(U+D800)"}, std::pair{"&#57343;", "(U+DFFF)"},
        std::pair{"&#xFFFE;", "(U+FFFE)"}, std::pair{"&#xffff;", "(U+FFFF)"},
        std::pair{"&#x110000;", "(past U+10FFFF)"}, std::pair{"&#4294967295;", "(past U+10FFFF)"}}) {
    testing_scenes::expectRefused(
        {reference,
         ("<scene name='s'>\n<box pos='0 1 0'\n name='a" + std::string(reference) + "b'/>\n</scene>").c_str(),
         3, "name", (std::string("holds the character reference ") + reference + " " + named).c_str()});
  }
  const scenes::Scene edges =
      scenes::loadSceneText("<scene name='&#xD7FF;&#xE000;&#xFFFD;&#x10000;&#x10FFFF;'/>", "edges.xml");
  EXPECT_EQ(edges.name, "\xED\x9F\xBF\xEE\x80\x80\xEF\xBF\xBD\xF0\x90\x80\x80\xF4\x8F\xBF\xBF");
  // Where it is no reference it stays text, as are references that are not zero.
  const scenes::Scene fine = scenes::loadSceneText(
      "<scene name='a&#48;&#x30;&#10;'><!-- &#0; --><?pi &#0;?><box name='x&amp;#0;' pos='0 1 0'/></scene>",
      "fine.xml");
  EXPECT_EQ(fine.name, "a00\n");
  EXPECT_EQ(fine.bodies.at(0).name, "x&#0;");
}

// pugixml reads no DOCTYPE and expands only XML's five entities: any other reference, declared or
// not, loaded as its own text (name='&a;' as "&a;"), so it is refused, naming where it stands.
TEST(SceneErrors, AnEntityReferenceTheLoaderWouldTakeAsTextIsRefused) {
  const std::string says = "holds the entity reference &a;, which would load as that text";
  testing_scenes::expectRefused(
      {"declared",
       "<!DOCTYPE scene [\n<!ENTITY a 'x'>\n]>\n<scene name='s'>\n<box pos='0 1 0'\n name='&a;'/>\n</scene>",
       6, "name", says.c_str()});
  testing_scenes::expectRefused({"undeclared", "<scene name='s'>\n<box pos='0 1 0'\n name='b&a;'/>\n</scene>",
                                 3, "name", says.c_str()});
  testing_scenes::expectRefused({"description", "<scene name='s'\n description='&nbsp;'>\n</scene>", 2,
                                 "description", "holds the entity reference &nbsp;"});
  testing_scenes::expectRefused(
      {"text", "<scene name='s'>\n<box pos='0 1 0'>\n&a;</box>\n</scene>", 3, "", says.c_str()});
  // XML's five are expanded; in a comment, a processing instruction or the DOCTYPE it is only text.
  const scenes::Scene fine = scenes::loadSceneText(
      "<!DOCTYPE scene [<!ENTITY a '&b;'> <!-- &c; ' --> ]>\n"
      "<scene name='&amp;a;&lt;&gt;&quot;&apos;'><!-- &a; --><?pi &a;?><box name='x&amp;y' pos='0 1 "
      "0'/></scene>",
      "fine.xml");
  EXPECT_EQ(fine.name, "&a;<>\"'");
  EXPECT_EQ(fine.bodies.at(0).name, "x&y");
}

// XML has an '&' start a reference (&name;, &#N;, &#xH;); pugixml kept one that starts none as
// text, so name='a & b' loaded where XML says the file is not well-formed. Refused, naming where
// it stands and what to write instead.
TEST(SceneErrors, AnAmpersandThatStartsNoReferenceIsRefused) {
  const char* says =
      "an '&' that starts no reference (&name;, &#N; or &#xH;): XML does not allow it; write &amp;";
  const struct {
    const char* value;
    const char* shown;
  } cases[] = {{"a & b", "'&'"},
               {"a&", "'&'"},
               {"&amp b", "'&amp'"},
               {"&lt", "'&lt'"},
               {"&#12", "'&#12'"},
               {"&#;", "'&#;'"},
               {"&#x;", "'&#x;'"},
               {"&#xG1;", "'&#x'"},
               {"&#X41;", "'&#'"},
               {"&;", "'&;'"},
               {"&abcdefghijklmnop", "'&abcdefghijk'"}};
  for (const auto& c : cases) {
    const std::string name = std::string("holds ") + c.shown + ", " + says;
    testing_scenes::expectRefused(
        {c.value,
         ("<scene name='s'>\n<box pos='0 1 0'\n name='" + std::string(c.value) + "'/>\n</scene>").c_str(), 3,
         "name", name.c_str()});
  }
  testing_scenes::expectRefused(
      {"description", "<scene name='s'\n description='salt & pepper'>\n</scene>", 2, "description", says});
  testing_scenes::expectRefused({"scene name", "<scene\n name='R&D'/>", 2, "name", says});
  testing_scenes::expectRefused(
      {"text", "<scene name='s'>\n<box pos='0 1 0'>\n& </box>\n</scene>", 3, "", "holds '&', an '&'"});
  testing_scenes::expectRefused({"after a DOCTYPE",
                                 "<!DOCTYPE scene [ <!ENTITY a 'x & y'> ]>\n<scene name='s'>\n<box pos='0 1 "
                                 "0'\n name='a&b'/>\n</scene>",
                                 4, "name", says});
  // Outside <scene> it is text where none may be, said as that where it stands.
  testing_scenes::expectRefused(
      {"after </scene>", "<scene name='s'>\n</scene>\nR & D", 3, "", "nothing may follow </scene>"});
  testing_scenes::expectRefused(
      {"before <scene>", "<?xml version='1.0'?>\n& <scene name='s'>\n</scene>", 2, "", "precede <scene>"});
  // Comments may end the file; text before them may not, an '&' in it or not.
  testing_scenes::expectRefused({"after </scene>, before a comment",
                                 "<scene name='s'>\n</scene>\nR & D\n<!-- c -->", 3, "",
                                 "nothing may follow </scene>"});
  testing_scenes::expectRefused({"text before a comment",
                                 "<scene name='s'>\n</scene>\n<!-- a -->\nstray\n<!-- b -->\n", 4, "",
                                 "nothing may follow </scene>"});
  EXPECT_NO_THROW(
      scenes::loadSceneText("<scene name='s'>\n</scene>\n<!-- a & b -->\n<?pi x?>\n<!-- c -->\n", "s.xml"));
  // The first in the file is said, whatever its kind: an entity reference further on does not hide it.
  testing_scenes::expectRefused(
      {"before an entity",
       "<scene name='s'>\n<box pos='0 1 0' name='a & b'/>\n<box pos='0 3 0' name='&c;'/>\n</scene>", 2,
       "name", says});
  // Not cut inside a character: a long name of two-byte letters is shown to a whole one.
  testing_scenes::expectRefused({"UTF-8",
                                 "<scene name='s'>\n<box pos='0 1 0'\n "
                                 "name='&\xC3\xA9\xC3\xA9\xC3\xA9\xC3\xA9\xC3\xA9\xC3\xA9 '/>\n</scene>",
                                 3, "name", "holds '&\xC3\xA9\xC3\xA9\xC3\xA9\xC3\xA9\xC3\xA9', an"});
}

// XML allows processing instructions before, inside and after the root element, and the loader
// skips them wherever they stand; the messages and docs/scene-format.md said only comments may
// follow </scene>. An XML declaration past the file's start and a DOCTYPE after </scene>, which XML
// does not allow, were taken (the second skipped unread); both are refused where they stand.
TEST(SceneErrors, ProcessingInstructionsAreSkippedWhereverTheyStand) {
  EXPECT_NO_THROW(scenes::loadSceneText(
      "<?xml version='1.0'?>\n<?pi a?>\n<!DOCTYPE scene>\n<?pi b?>\n<scene name='s'>\n<?pi c?>\n"
      "<particle pos='0 1 0'/>\n</scene>\n<?pi d?>\n<!-- e -->\n",
      "s.xml"));
  testing_scenes::expectRefused(
      {"text after a processing instruction", "<scene name='s'>\n</scene>\n<?pi x?>\njunk\n", 4, "",
       "nothing may follow </scene> but comments, processing instructions and white space"});
  // The first element is taken for the root: the <scene> after it is the one said.
  testing_scenes::expectRefused(
      {"element before the root", "<box pos='0 1 0'/>\n<scene name='s'>\n</scene>\n", 2, "",
       "nothing may follow or precede <scene> but comments and processing instructions"});
  testing_scenes::expectRefused({"declaration after the root",
                                 "<scene name='s'>\n</scene>\n<?xml version='1.0'?>\n", 3, "",
                                 "an XML declaration (<?xml ...?>) may only start the file"});
  testing_scenes::expectRefused({"declaration after a comment",
                                 "<!-- c -->\n<?xml version='1.0'?>\n<scene name='s'/>\n", 2, "",
                                 "an XML declaration (<?xml ...?>) may only start the file"});
  testing_scenes::expectRefused({"DOCTYPE after the root", "<scene name='s'>\n</scene>\n<!DOCTYPE scene>\n",
                                 3, "", "a <!DOCTYPE> may only precede <scene>"});
}

// Text after </scene> that ends as a processing instruction or a comment ends ("junk?>", "junk-->")
// is still text: the start of the instruction or comment it seems to close (an XML declaration, a
// comment inside <scene>) lies before the root's end, not after it.
TEST(SceneErrors, TextAfterTheRootEndingAsMarkupEndsIsRefusedWithItsLine) {
  const char* says = "nothing may follow </scene> but comments, processing instructions and white space";
  testing_scenes::expectRefused(
      {"after a declaration", "<?xml version='1.0'?>\n<scene name='s'>\n</scene>\njunk?>\n", 4, "", says});
  testing_scenes::expectRefused({"after a processing instruction in the scene",
                                 "<scene name='s'>\n<?pi a?>\n</scene>\n\n  junk ?>", 5, "", says});
  testing_scenes::expectRefused(
      {"after a comment in the scene", "<scene name='s'><!-- c -->\n</scene>\njunk-->\n", 3, "", says});
  testing_scenes::expectRefused({"between two processing instructions",
                                 "<?xml version='1.0'?>\n<scene name='s'/>\n<?pi a?>junk<?pi b?>\n", 3, "",
                                 says});
  // A '>' in a value or in a comment inside <scene> does not end its tag or the root early.
  EXPECT_NO_THROW(scenes::loadSceneText(
      "<?xml version='1.0'?>\n<scene name='a>b' description=\"c?>d\"><!-- e > f -->\n<particle pos='0 1 "
      "0'/></scene>\n<?pi g?>\n",
      "s.xml"));
}

// Text before <scene> is refused as text after </scene> is (pugixml drops both unread: plain words
// before the root loaded without a word), and only XML's white space (space, tab, CR, LF) may stand
// beside the root: a form feed or vertical tab, which XML allows nowhere, passed there as space.
TEST(SceneErrors, TextBeforeTheRootIsRefusedWithItsLine) {
  const char* says = "nothing may precede <scene> but comments, processing instructions and white space";
  testing_scenes::expectRefused({"at the start", "junk\n<scene name='s'>\n</scene>\n", 1, "", says});
  testing_scenes::expectRefused(
      {"after a declaration", "<?xml version='1.0'?>\n\n junk\n<scene name='s'/>\n", 3, "", says});
  testing_scenes::expectRefused({"after a comment", "<!-- c -->junk<scene name='s'/>\n", 1, "", says});
  testing_scenes::expectRefused(
      {"after a DOCTYPE", "<!DOCTYPE scene [ <!ENTITY a '>'> ]>\nx\n<scene name='s'/>\n", 2, "", says});
  testing_scenes::expectRefused({"a vertical tab before", "\v<scene name='s'/>\n", 1, "", says});
  testing_scenes::expectRefused(
      {"a form feed after", "<scene name='s'/>\n\f\n", 2, "",
       "nothing may follow </scene> but comments, processing instructions and white space"});
  // A byte order mark, and XML's own white space, are no text.
  EXPECT_NO_THROW(scenes::loadSceneText(
      "\xEF\xBB\xBF<?xml version='1.0'?>\r\n\t <!-- c -->\n<scene name='s'/>\r\n", "s.xml"));
}

// In a comment, CDATA, a processing instruction or the DOCTYPE an '&' is only text, as XML has it:
// nothing there is refused for it, and a reference XML allows loads as what it stands for.
TEST(SceneErrors, AnAmpersandOutsideValuesAndTextIsOnlyText) {
  const scenes::Scene fine = scenes::loadSceneText(
      "<?xml version='1.0' encoding='UTF-8'?>\n"
      "<!DOCTYPE scene [ <!ENTITY a 'x & y'> <!-- & --> <?pi & ?> ]>\n"
      "<!-- R & D -->\n"
      "<scene name='&amp;&#38;&#x26;&lt;'><!-- a & b --><?pi & ?><box name='&#233;' pos='0 1 0'/></scene>\n"
      "<!-- & -->",
      "fine.xml");
  EXPECT_EQ(fine.name, "&&&<");
  EXPECT_EQ(fine.bodies.at(0).name, "\xC3\xA9");
  // CDATA is text the scene refuses where it stands; refused as that, not for its '&'.
  testing_scenes::expectRefused({"CDATA in <scene>", "<scene name='s'>\n<![CDATA[ a & b ]]>\n</scene>", 2, "",
                                 "unexpected text inside <scene>"});
  testing_scenes::expectRefused({"CDATA in <box>",
                                 "<scene name='s'>\n<box pos='0 1 0'><![CDATA[&]]></box>\n</scene>", 2, "",
                                 "takes no child elements or text"});
}

// pugixml keeps a '<' in an attribute's value as text, where XML does not allow one: name="a<b"
// loaded, and a tool that reads XML as XML would refuse the file. Refused where it stands, in a
// value quoted either way, whatever the other quote or a '>' before it.
TEST(SceneErrors, ALessThanInAnAttributeValueIsRefused) {
  const char* says =
      "holds '<', which XML does not allow in an attribute value; write &lt; for the character '<'";
  for (const char* value : {"'a<b'", "\"a<b\"", "'<'", "'say \"<\"'", "\"it's a>b<c\"", "'&lt;<'"}) {
    testing_scenes::expectRefused(
        {value, (std::string("<scene name='s'>\n<box pos='0 1 0'\n name=") + value + "/>\n</scene>").c_str(),
         3, "name", says});
  }
  testing_scenes::expectRefused(
      {"after other attributes",
       "<scene name='s'>\n<box name='a>b' pos='0 1 0'\n model='corners<'/>\n</scene>", 3, "model", says});
  testing_scenes::expectRefused(
      {"description", "<scene name='s'\n description='1 < 2'>\n</scene>", 2, "description", says});
  testing_scenes::expectRefused(
      {"a later element",
       "<scene name='s' description='it\"s'>\n<box pos='0 1 0' name='&lt;'/>\n<box pos='0 3 "
       "0'\n name='b<'/>\n</scene>",
       4, "name", says});
  // The first in the file is said, whatever its kind: a bad '&' after it does not hide it.
  testing_scenes::expectRefused(
      {"before an '&'",
       "<scene name='s'>\n<box pos='0 1 0' name='a<b'/>\n<box pos='0 3 0' name='&'/>\n</scene>", 2, "name",
       says});
  testing_scenes::expectRefused(
      {"after an '&'",
       "<scene name='s'>\n<box pos='0 1 0' name='a&b'/>\n<box pos='0 3 0' name='<'/>\n</scene>", 2, "name",
       "holds '&b'"});
}

// Outside a tag a '<' starts markup, and in a comment, CDATA, a processing instruction or the
// DOCTYPE it is only text, quotes and all: nothing there is refused for it.
TEST(SceneErrors, ALessThanOutsideAttributeValuesIsNotRefusedForIt) {
  const scenes::Scene fine = scenes::loadSceneText(
      "<?xml version='1.0' encoding='UTF-8'?>\n"
      "<!DOCTYPE scene [ <!ENTITY a '<'> <!-- \" < --> <?pi ' < ?> ]>\n"
      "<!-- it's a < b -->\n"
      "<scene name='&lt;&#60;&#x3C;' description='a > b'><!-- ' < --><?pi \" <?><box name='x>y' pos='0 1 "
      "0'/>\n<box name=\"it's\" pos='0 3 0'/></scene>\n"
      "<!-- \" < -->",
      "fine.xml");
  EXPECT_EQ(fine.name, "<<<");
  EXPECT_EQ(fine.description, "a > b");
  EXPECT_EQ(fine.bodies.at(0).name, "x>y");
  EXPECT_EQ(fine.bodies.at(1).name, "it's");
  testing_scenes::expectRefused({"CDATA in <box>",
                                 "<scene name='s'>\n<box pos='0 1 0'><![CDATA[ ' < ]]></box>\n</scene>", 2,
                                 "", "takes no child elements or text"});
}

// "&1a;", "&-a;" and "&.5;" start no name, so they are no reference, yet they end as an entity
// reference does: two refusals at one '&'. Each is said as the entity reference it looks like.
TEST(SceneErrors, AnAmpersandBothAnEntityAndNoReferenceIsSaidAsTheEntity) {
  for (const std::string reference : {"&1a;", "&-a;", "&.5;"}) {
    testing_scenes::expectRefused(
        {reference.c_str(),
         ("<scene name='s'>\n<box pos='0 1 0'\n name='" + reference + "'/>\n</scene>").c_str(), 3, "name",
         ("holds the entity reference " + reference + ",").c_str()});
  }
}

// A quote in a processing instruction or a conditional section of the DOCTYPE is only text there,
// as pugixml reads it; taken for the start of a quoted value, it would hide every reference after
// it from the check, and name='&a;' would load as that text, name='a&#0;b' as "a".
TEST(SceneErrors, AQuoteInsideTheDoctypesInstructionsHidesNoReference) {
  for (const char* inside : {"<?pi it's?>", "<![IGNORE[ it's ]]>", "<![IGNORE[ <![ \" ]]> ' ]]>"}) {
    const std::string doctype = std::string("<!DOCTYPE scene [\n") + inside + "\n]>\n";
    testing_scenes::expectRefused(
        {inside, (doctype + "<scene name='s'>\n<box pos='0 1 0'\n name='&a;'/>\n</scene>").c_str(), 6, "name",
         "holds the entity reference &a;"});
    testing_scenes::expectRefused(
        {inside, (doctype + "<scene name='s'>\n<box pos='0 1 0'\n name='a&#0;b'/>\n</scene>").c_str(), 6,
         "name", "holds the character reference &#0;"});
    // And the DOCTYPE still ends where pugixml ends it: what follows loads.
    EXPECT_EQ(scenes::loadSceneText(doctype + "<scene name='s&amp;'/>", "fine.xml").name, "s&") << inside;
  }
}

// 1e-400 is finite but nearer zero than any double; refused as too small, not as "not finite".
TEST(SceneErrors, ANumberThatUnderflowsIsSaidToBeTooSmall) {
  for (const char* value : {"1e-400", "-1e-400", "+0.000001e-320", "1000e-330", "1e-99999999999999999999"}) {
    const std::string says = "'" + std::string(value) + "' is too small to represent";
    testing_scenes::expectRefused(
        {value,
         ("<scene name='s'>\n<box pos='0 1 0'\n mass='" + std::string(value) + "'/>\n</scene>").c_str(), 3,
         "mass", says.c_str()});
    testing_scenes::expectRefused(
        {value, ("<scene name='s'>\n<box\n pos='0 " + std::string(value) + " 0'/>\n</scene>").c_str(), 3,
         "pos", says.c_str()});
  }
  for (const char* value : {"1e400", "0.001e312", "1e99999999999999999999", "x"}) {
    testing_scenes::expectRefused(
        {value,
         ("<scene name='s'>\n<box pos='0 1 0'\n mass='" + std::string(value) + "'/>\n</scene>").c_str(), 3,
         "mass", "is not a finite number"});
  }
}

// The values the loader splits itself (a stick's length, a share of part-strengths, a turn of
// held-turns) or reads beside a word (depenetration-speed's none) say so too.
TEST(SceneErrors, ANumberThatUnderflowsIsTooSmallInEveryAttribute) {
  const std::string says = "'1e-400' is too small to represent (the smallest besides 0 is 4.94066e-324)";
  const std::string particles =
      "<scene name='s'>\n<particle name='p' pos='0 1 0'/><particle name='q' pos='0 2 0'/>\n";
  testing_scenes::expectRefused({"length",
                                 (particles + "<stick a='p' b='q'\n length='1e-400'/>\n</scene>").c_str(), 4,
                                 "length", (says + " (m)").c_str()});
  testing_scenes::expectRefused({"depenetration-speed",
                                 "<scene name='s'>\n<solver\n depenetration-speed='1e-400'/>\n</scene>", 3,
                                 "depenetration-speed", (says + " (m/s)").c_str()});
  const std::string character =
      "<scene name='s'>\n<ragdoll name='r' pos='0 1 0'/>\n"
      "<character ragdoll='r' clip='" DATA_DIR "/assets/clips/run.bvh'\n ";
  testing_scenes::expectRefused({"part-strengths",
                                 (character + "part-strengths='head=1e-400'/>\n</scene>").c_str(), 4,
                                 "part-strengths", says.c_str()});
  testing_scenes::expectRefused({"held-turns",
                                 (character + "blend='0.5' held-turns='1e-400 0 0 1'/>\n</scene>").c_str(), 4,
                                 "held-turns", says.c_str()});
}
