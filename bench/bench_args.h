// The one command-line parser of every benchmark program: each option is declared once, with its
// name, its value's name, a help line and the variable it sets, so --help and the errors come
// from the same list and cannot drift from what the program accepts.
#pragma once

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace bench {

/// `text` as a number or string into `target`; an error, or "" when it took it. Numbers must be the
/// whole text: "5x" or "" is an error, not 5 or 0 as atoi would have it.
template <class T>
std::string ParseValue(const std::string& text, T* target) {
  if constexpr (std::is_same_v<T, std::string>) {
    *target = text;
    return "";
  } else {
    static_assert(std::is_arithmetic_v<T>, "Args: an option's target is a number or a string");
    T value{};
    const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (status == std::errc::result_out_of_range) return "\"" + text + "\" is out of range";
    if (status != std::errc() || end != text.data() + text.size()) {
      return "\"" + text + "\" is not " + (std::is_integral_v<T> ? "a whole number" : "a number");
    }
    *target = value;
    return "";
  }
}

class Args {
 public:
  /// Sets one option from its value text (flags get none); returns an error, or "" when it took it.
  using Setter = std::function<std::string(const std::string&)>;

  /// `program` names the program in --help and errors; `about` is --help's first line.
  Args(std::string program, std::string about) : program_(std::move(program)), about_(std::move(about)) {}

  /// `spec` is the option as --help shows it: "--quick" for a flag.
  Args& Flag(const std::string& spec, bool* target, std::string help) {
    return Flag(spec, [target] { *target = true; }, std::move(help));
  }

  /// A flag that sets several things where it stands (bench_broadphase's --quick), so later options win.
  Args& Flag(const std::string& spec, std::function<void()> action, std::string help) {
    return Add(spec, false, std::move(help), [action](const std::string&) { action(); return std::string(); });
  }

  /// `spec` is "--repeats R": the option, then its value's name.
  template <class T>
  Args& Value(const std::string& spec, T* target, std::string help) {
    return Add(spec, true, std::move(help), [target](const std::string& text) { return ParseValue(text, target); });
  }

  /// As above for a whole number, where one below `at_least` is raised to it (what the programs did
  /// before this parser; --help says so).
  template <class T>
  Args& Value(const std::string& spec, T* target, std::string help, std::type_identity_t<T> at_least) {
    static_assert(std::is_integral_v<T>, "Args: only whole numbers have a least value");
    const Setter set = [target, at_least](const std::string& text) {
      std::string error = ParseValue(text, target);
      if (error.empty()) *target = std::max(*target, at_least);
      return error;
    };
    return Add(spec, true, Note(std::move(help), "at least " + std::to_string(at_least)), set);
  }

  /// One of a list of words, each naming a value; several words may name one (an old name kept).
  template <class T>
  Args& Choice(const std::string& spec, T* target, std::type_identity_t<std::vector<std::pair<std::string, T>>> words,
               std::string help) {
    std::string list;
    for (const auto& [word, value] : words) list += (list.empty() ? "" : "|") + word;
    return Add(spec, true, Note(std::move(help), list), [target, words, list](const std::string& text) {
      for (const auto& [word, value] : words) {
        if (word == text) return *target = value, std::string();
      }
      return "unknown value \"" + text + "\" (expected one of " + list + ")";
    });
  }

  /// A value with its own rule: `set` returns an error or "".
  Args& Custom(const std::string& spec, Setter set, std::string help) {
    return Add(spec, true, std::move(help), std::move(set));
  }

  /// An argument without a dash, taken in declaration order; all are optional.
  template <class T>
  Args& Positional(std::string name, T* target, std::string help) {
    positionals_.push_back({std::move(name), "", std::move(help),
                            [target](const std::string& text) { return ParseValue(text, target); }});
    return *this;
  }

  /// Empty: run the program. Otherwise the program ends with this exit code: 0 after printing --help,
  /// 2 after printing a one-line error.
  std::optional<int> Parse(int argc, char** argv) const {
    std::size_t positional = 0;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h") return std::printf("%s", Help().c_str()), 0;
      if (arg.size() > 1 && arg[0] == '-') {
        const Option* option = Find(arg);
        if (option == nullptr) return Error("unknown option " + arg);
        if (option->value.empty()) {
          option->set("");
          continue;
        }
        if (i + 1 >= argc) return Error(arg + " needs a value (" + option->value + ")");
        if (std::string error = option->set(argv[++i]); !error.empty()) return Error(arg + ": " + error);
      } else if (positional < positionals_.size()) {
        const Option& p = positionals_[positional++];
        if (std::string error = p.set(arg); !error.empty()) return Error(p.name + ": " + error);
      } else {
        return Error("unexpected argument \"" + arg + "\"");
      }
    }
    return std::nullopt;
  }

  /// Prints "error: MESSAGE (PROGRAM --help lists the options)" and gives exit code 2, for the checks
  /// a program makes after Parse.
  int Error(const std::string& message) const {
    std::fprintf(stderr, "error: %s (%s --help lists the options)\n", message.c_str(), program_.c_str());
    return 2;
  }

  std::string Help() const {
    std::string text = "usage: " + program_ + (options_.empty() ? "" : " [options]");
    for (const Option& p : positionals_) text += " [" + p.name + "]";
    text += "\n" + about_ + "\n\n";
    std::vector<Option> all = positionals_;
    all.insert(all.end(), options_.begin(), options_.end());
    all.push_back({"-h, --help", "", "print this text and exit", nullptr});
    std::size_t width = 0;
    for (const Option& o : all) width = std::max(width, Spec(o).size());
    for (const Option& o : all) text += "  " + Spec(o) + std::string(width + 2 - Spec(o).size(), ' ') + o.help + "\n";
    return text;
  }

 private:
  struct Option {
    std::string name;   // "--repeats", or a positional's "STEPS"
    std::string value;  // "R"; empty for a flag
    std::string help;
    Setter set;
  };

  Args& Add(const std::string& spec, bool takes_value, std::string help, Setter set) {
    const std::size_t space = spec.find(' ');
    std::string value = takes_value ? (space == std::string::npos ? "VALUE" : spec.substr(space + 1)) : "";
    options_.push_back({spec.substr(0, space), std::move(value), std::move(help), std::move(set)});
    return *this;
  }

  // "help (default 5)" and "at least 1" give "help (default 5, at least 1)".
  static std::string Note(std::string help, const std::string& note) {
    if (!help.empty() && help.back() == ')') return help.insert(help.size() - 1, ", " + note);
    return help + " (" + note + ")";
  }

  static std::string Spec(const Option& o) { return o.value.empty() ? o.name : o.name + " " + o.value; }

  const Option* Find(const std::string& name) const {
    for (const Option& o : options_) {
      if (o.name == name) return &o;
    }
    return nullptr;
  }

  std::string program_;
  std::string about_;
  std::vector<Option> options_;
  std::vector<Option> positionals_;
};

/// The options of every program that prints tables and writes CSV files: a smoke run, the
/// number of timed repeats and the CSV folder. A program's Options derive from it.
struct RunOptions {
  explicit RunOptions(int default_repeats) : repeats(default_repeats) {}

  /// Declares --quick, --repeats R (at least 1) and --out DIR; the help lines say what a smoke run
  /// leaves out and what one repeat is.
  void AddTo(Args& args, const std::string& quick_help, const std::string& repeats_help) {
    args.Flag("--quick", &quick, "smoke run: " + quick_help)
        .Value("--repeats R", &repeats, repeats_help + " (default " + std::to_string(repeats) + ")", 1)
        .Value("--out DIR", &out_dir, "folder for the CSV files (default " + out_dir + ")");
  }

  bool quick = false;
  int repeats;
  std::string out_dir = "bench-out";
};

}  // namespace bench
