// The benchmark programs' argument parser (bench/bench_args.h): values, the clamps the programs
// always had, the old solver name as an alias, and exit code 2 for every kind of bad input.
#include <catch2/catch.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_args.h"

namespace {

struct Parsed {
  bool quick = false;
  int repeats = 5;
  double seconds = 0.5;
  std::string out = "bench-out";
  std::optional<int> solver;
  std::int64_t steps = 1000;
  std::uint64_t seed = 1;
};

bench::Args Declare(Parsed& p) {
  bench::Args args("bench_test", "a test program");
  args.Flag("--quick", &p.quick, "smoke run")
      .Value("--repeats R", &p.repeats, "timed runs", 1)
      .Value("--seconds S", &p.seconds, "a sample's length")
      .Value("--out DIR", &p.out, "CSV folder")
      .Choice("--solver NAME", &p.solver, {{"sequential_impulse", 0}, {"seed", 0}, {"substep", 1}}, "the solver")
      .Positional("STEPS", &p.steps, "steps")
      .Positional("SEED", &p.seed, "seed");
  return args;
}

std::optional<int> Run(Parsed& p, std::vector<std::string> words) {
  words.insert(words.begin(), "bench_test");
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  return Declare(p).Parse(static_cast<int>(argv.size()), argv.data());
}

}  // namespace

TEST_CASE("bench arguments: values land in their variables, defaults stay otherwise", "[bench]") {
  Parsed p;
  REQUIRE_FALSE(Run(p, {}).has_value());
  CHECK(p.repeats == 5);
  CHECK(p.out == "bench-out");
  CHECK_FALSE(p.solver.has_value());

  REQUIRE_FALSE(Run(p, {"--quick", "--repeats", "3", "--seconds", "0.25", "--out", "x y", "200", "7"}).has_value());
  CHECK(p.quick);
  CHECK(p.repeats == 3);
  CHECK(p.seconds == 0.25);
  CHECK(p.out == "x y");
  CHECK(p.steps == 200);
  CHECK(p.seed == 7);
}

TEST_CASE("bench arguments: a number below the least is raised to it, as the programs always did", "[bench]") {
  Parsed p;
  REQUIRE_FALSE(Run(p, {"--repeats", "0"}).has_value());
  CHECK(p.repeats == 1);
  REQUIRE_FALSE(Run(p, {"--repeats", "-4"}).has_value());
  CHECK(p.repeats == 1);
}

TEST_CASE("bench arguments: the sequential-impulse solver by its name and by its old name seed", "[bench]") {
  for (const char* name : {"sequential_impulse", "seed"}) {
    Parsed p;
    REQUIRE_FALSE(Run(p, {"--solver", name}).has_value());
    CHECK(p.solver == 0);
  }
  Parsed p;
  REQUIRE_FALSE(Run(p, {"--solver", "substep"}).has_value());
  CHECK(p.solver == 1);
}

TEST_CASE("bench arguments: bad input ends the program with exit code 2", "[bench]") {
  const std::vector<std::vector<std::string>> bad = {
      {"--repeat", "3"},       // unknown option
      {"--repeats"},           // missing value
      {"--repeats", "3x"},     // a number followed by more text
      {"--repeats", ""},       // an empty value
      {"--seconds", "fast"},   // not a number
      {"--solver", "soft"},    // not one of the words
      {"1000", "-1"},          // a dash starts an option, and there is no option -1
      {"1000", "x"},           // a positional that is not a number
      {"1000", "1", "extra"},  // one positional too many
  };
  for (const std::vector<std::string>& words : bad) {
    INFO(words.front() << (words.size() > 1 ? " " + words[1] : ""));
    Parsed p;
    CHECK(Run(p, words) == 2);
  }
}

TEST_CASE("bench arguments: --help lists every option and ends the program with exit code 0", "[bench]") {
  Parsed p;
  const std::string help = Declare(p).Help();
  for (const char* line : {"usage: bench_test [options] [STEPS] [SEED]", "--quick", "--repeats R",
                           "timed runs (at least 1)", "--solver NAME", "sequential_impulse|seed|substep", "-h, --help"}) {
    CHECK(help.find(line) != std::string::npos);
  }
  CHECK(Run(p, {"--help"}) == 0);
  CHECK(Run(p, {"-h"}) == 0);
}
