// The pbm command line as a user meets it: exit codes (0 ok, 1 simulation failed, 2 bad input),
// messages that name the file and the JSON path, bit-identical reruns, and no NaN in any output
// at the numerical extremes.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

using Result = pbm::test::CliResult;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("pbm_cli_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

Result pbm(const std::string& args) {
  return pbm::test::run_pbm(args);
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string scene(const std::string& name) {
  return std::string(PBM_SOURCE_DIR) + "/scenes/" + name + ".json";
}

// Writes a scene text into the temp dir and returns its path.
std::string write_scene(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p.string();
}

const char* kBall = R"({
  "name": "cli-ball", "solver": {"dt": 0.005, "fps": 20},
  "bodies": [{"name": "b", "level": "local", "position": [0, 0, 2],
              "shape": {"kind": "superquadric", "q_s": {"eps1": EPS1}, "stiffness": [1e4, 1e4, 1e4, 1e4, 1e3, 1e3]},
              "tessellation": {"rings": 6, "segments": 6},
              "material": {"w0": 20, "w1": W1, "mass": MASS, "damping": 1.0}}],
  "obstacles": [{"kind": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "elasticity": 500, "friction": 0.3}]
})";

std::string ball(const std::string& eps1, const std::string& w1, const std::string& mass) {
  std::string s = kBall;
  s.replace(s.find("EPS1"), 4, eps1);
  s.replace(s.find("W1"), 2, w1);
  s.replace(s.find("MASS"), 4, mass);
  return s;
}

TEST(Cli, ValidateAcceptsEveryShippedScene) {
  for (const char* name :
       {"jello-ball", "rugby-ball", "morphing-shell", "interactive", "snowman", "dragonfly",
        "seesaw", "pendulum-chain", "rope-drop", "waist-smooth", "waist-step", "desk"}) {
    const Result r = pbm("validate " + scene(name));
    EXPECT_EQ(r.code, 0) << name << ": " << r.output;
  }
}

// Same scene and settings => byte-identical states.jsonl (single-threaded determinism).
TEST(Cli, TwoRunsOfEachSceneWriteIdenticalStates) {
  const fs::path dir = temp_dir();
  for (const auto& [name, frames] : {std::pair{"jello-ball", 40},
                                     {"rugby-ball", 30},
                                     {"morphing-shell", 30},
                                     {"interactive", 2},
                                     {"pendulum-chain", 30},
                                     {"waist-step", 30}}) {
    const fs::path a = dir / (std::string(name) + "_a.jsonl");
    const fs::path b = dir / (std::string(name) + "_b.jsonl");
    const std::string common = "simulate " + scene(name) + " --frames " + std::to_string(frames);
    ASSERT_EQ(pbm(common + " --out " + a.string()).code, 0) << name;
    ASSERT_EQ(pbm(common + " --out " + b.string()).code, 0) << name;
    const std::string sa = read(a), sb = read(b);
    EXPECT_GT(sa.size(), 1000u) << name;
    EXPECT_TRUE(sa == sb) << name << ": states differ between two runs";
  }
}

TEST(Cli, WritesStatsAndAMeshSequence) {
  const fs::path dir = temp_dir() / "outputs";
  const Result r = pbm("simulate " + scene("jello-ball") + " --frames 3 --stats " +
                       (dir / "stats.json").string() + " --mesh-dir " + (dir / "meshes").string() +
                       " --mesh-format ply");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string stats = read(dir / "stats.json");
  for (const char* key : {"\"time\"", "\"wall_seconds\"", "\"substeps\"", "\"kinetic_energy\"",
                          "\"elastic_energy\"", "\"min_obstacle_distance\"", "\"q_s\""}) {
    EXPECT_NE(stats.find(key), std::string::npos) << key;
  }
  // A figure's energies and contacts, and its joint coordinates in the states.
  const Result chain =
      pbm("simulate " + scene("pendulum-chain") + " --frames 3 --stats " +
          (dir / "chain.json").string() + " --out " + (dir / "chain.jsonl").string());
  ASSERT_EQ(chain.code, 0) << chain.output;
  const std::string chain_stats = read(dir / "chain.json");
  for (const char* key : {"\"figures\"", "\"potential_energy\"", "\"contacts\""}) {
    EXPECT_NE(chain_stats.find(key), std::string::npos) << key;
  }
  EXPECT_NE(read(dir / "chain.jsonl").find("\"figures\":[{\"name\":\"chain\",\"q\":["),
            std::string::npos);
  // A controlled figure's plot (figs. 15.7, 15.8): desired, reference model and actual.
  ASSERT_EQ(pbm("simulate " + scene("waist-step") + " --frames 3 --stats " +
                (dir / "waist.json").string())
                .code,
            0);
  const std::string waist = read(dir / "waist.json");
  for (const char* key : {"\"controllers\"", "\"desired\"", "\"reference\"", "\"actual\"",
                          "\"output\"", "\"saturated\"", "\"actuator_work\""}) {
    EXPECT_NE(waist.find(key), std::string::npos) << key;
  }
  for (int f = 0; f <= 3; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.ply", f);
    EXPECT_TRUE(fs::exists(dir / "meshes" / name)) << name;
  }
}

// `pbm bench realtime` reports a row per scene of the folder; a folder without scenes is bad
// input. (What the factors are is measured, not asserted: speed belongs to benchmarks.)
TEST(Cli, BenchRealtimeReportsEveryScene) {
  const fs::path dir = temp_dir() / "realtime";
  fs::create_directories(dir);
  fs::copy_file(scene("jello-ball"), dir / "jello-ball.json", fs::copy_options::overwrite_existing);
  const Result r = pbm("bench realtime " + dir.string() + " --seconds 0.2");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::size_t row = r.output.find("\njello-ball ");
  ASSERT_NE(row, std::string::npos) << r.output;
  double fps = 0, whole = 0;
  long frames = 0;
  ASSERT_EQ(
      std::sscanf(r.output.c_str() + row + 1, "jello-ball %lf %ld %lf", &fps, &frames, &whole), 3)
      << r.output;
  EXPECT_EQ(frames, std::lround(0.2 * fps));
  EXPECT_GT(whole, 0);
  const fs::path empty = temp_dir() / "no_scenes";
  fs::create_directories(empty);
  EXPECT_EQ(pbm("bench realtime " + empty.string()).code, 2);
}

struct BadInput {
  std::string name, text, expected;
};

// Bad input: exit 2 and a message naming the file and the field path.
TEST(Cli, BadInputExitsTwoNamingFileAndField) {
  const std::vector<BadInput> cases = {
      {"malformed.json", "{\"bodies\": [", "malformed.json"},
      {"unknown.json", "{\"bodies\": [{\"material\": {\"mass\": 1}}], \"colour\": 1}", "colour"},
      {"negative-mass.json", ball("1.0", "15", "-2"), "bodies[0].material.mass: must be > 0"},
      {"eps-zero.json", ball("0.0", "15", "1"), "bodies[0].shape.q_s.eps1"},
      {"w1-negative.json", ball("1.0", "-1", "1"), "bodies[0].material.w1"},
      {"constraint-missing-body.json",
       "{\"bodies\": [{\"name\": \"b\", \"material\": {\"mass\": 1}}], \"constraints\": "
       "[{\"name\": \"neck\", \"a\": {\"body\": \"head\", \"node\": 0}, "
       "\"b\": {\"world\": [0, 0, 1]}}]}",
       "constraints[0].a.body: unknown body 'head'"},
      {"figure-cycle.json",
       "{\"figures\": [{\"segments\": [{\"name\": \"a\", \"parent\": \"b\"}, "
       "{\"name\": \"b\", \"parent\": \"a\"}]}]}",
       "figures[0].segments[0].parent: the parents form a cycle"},
      {"figure-axis.json", "{\"figures\": [{\"segments\": [{\"joint\": {\"axis\": [0, 0, 0]}}]}]}",
       "figures[0].segments[0].joint.axis: must be a nonzero vector"},
      {"figure-massless.json", "{\"figures\": [{\"segments\": [{\"density\": 0}]}]}",
       "figures[0].segments[0].density: must be > 0"},
      // Hostile files of a few KB (scenes/README.md, "Limits").
      {"deep.json", "{\"bodies\": " + std::string(10000, '[') + std::string(10000, ']') + "}",
       "nested deeper than 32"},
      {"rings.json",
       "{\"bodies\": [{\"tessellation\": {\"rings\": 1000000000}, \"material\": "
       "{\"mass\": 1}}]}",
       "bodies[0].tessellation.rings: must be <= 4096"},
  };
  for (const BadInput& c : cases) {
    const std::string path = write_scene(c.name, c.text);
    for (const char* verb : {"validate ", "simulate "}) {
      const Result r = pbm(verb + path);
      EXPECT_EQ(r.code, 2) << c.name << ": " << r.output;
      EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.name << ": " << r.output;
      EXPECT_NE(r.output.find(c.name), std::string::npos) << c.name << ": " << r.output;
    }
  }
  const Result missing = pbm("simulate /nonexistent/scene-file.json");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find("scene-file.json"), std::string::npos) << missing.output;
  const Result unwritable =
      pbm("simulate " + scene("jello-ball") + " --frames 1 --out /proc/nope/s.jsonl");
  EXPECT_EQ(unwritable.code, 2) << unwritable.output;
  const Result bad_integrator = pbm("simulate " + scene("jello-ball") + " --integrator leapfrog");
  EXPECT_EQ(bad_integrator.code, 2) << bad_integrator.output;
}

// Extremes: either a valid run (exit 0) or a clean failure (exit 1 with a message naming the
// body), never a crash, never a NaN written.
TEST(Cli, ExtremeParametersRunOrFailCleanlyWithoutNaN) {
  struct Extreme {
    std::string name, text, extra;
  };
  std::string taper_pos = ball("1.0", "15", "1");
  taper_pos.replace(taper_pos.find("\"superquadric\""), 14, "\"taper_bend\"");
  taper_pos.replace(taper_pos.find("\"q_s\": {"), 8,
                    "\"q_s\": {\"t1\": 1.0, \"t2\": -1.0, \"b1\": 0.5, \"b2\": 1.0, \"b3\": 1.0, ");
  taper_pos.replace(taper_pos.find("[1e4, 1e4, 1e4, 1e4, 1e3, 1e3]"), 30, "{\"a0\": 1e4}");
  std::string bend_neg = taper_pos;
  bend_neg.replace(bend_neg.find("\"b2\": 1.0"), 9, "\"b2\": -1.0");
  bend_neg.replace(bend_neg.find("\"b3\": 1.0"), 9, "\"b3\": 1e-6");
  const std::vector<Extreme> cases = {
      {"w1-tiny.json", ball("1.0", "1e-3", "1"), ""},
      {"w1-huge.json", ball("1.0", "1e6", "1"), ""},
      {"eps-small.json", ball("0.1", "15", "1"), ""},
      {"eps-large.json", ball("4.0", "15", "1"), ""},
      {"taper-bend-limits.json", taper_pos, ""},
      {"bend-range-limit.json", bend_neg, ""},
      // Explicit limit for the membrane: omega_max^2 ~ 8 w1 / (m_i a^2); 2x past it.
      {"dt-twice-limit.json", ball("1.0", "1e4", "1"), " --dt 0.02"},
  };
  for (const Extreme& c : cases) {
    const std::string path = write_scene(c.name, c.text);
    const fs::path out = temp_dir() / (c.name + ".jsonl");
    const Result r = pbm("simulate " + path + " --seconds 1 --out " + out.string() + c.extra);
    EXPECT_TRUE(r.code == 0 || r.code == 1) << c.name << ": exit " << r.code << " " << r.output;
    if (r.code == 1) {
      EXPECT_NE(r.output.find("body 'b'"), std::string::npos) << c.name << r.output;
    }
    const std::string states = read(out);
    EXPECT_EQ(states.find("nan"), std::string::npos) << c.name;
    EXPECT_EQ(states.find("inf"), std::string::npos) << c.name;
    EXPECT_FALSE(states.empty()) << c.name;
  }
}

}  // namespace
