#include "registry.h"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <new>
#include <nlohmann/json.hpp>
#include <string_view>

#include "coons/config.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

namespace coons::cli {

namespace {

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

int fail(int status, const std::string& message) {
  std::cerr << "error: " << one_line(message) << '\n';
  return status;
}

// Every option and positional that takes a value refuses an empty one: CLI11 converts "" to 0
// for a number (`--alpha ''` solved the Laplace net, `--threads ''` used every core), and no
// file name, folder or backend name is empty either. A number too small for a double is refused.
void refuse_empty_values(CLI::App& app) {
  const CLI::Validator non_empty(
      [](std::string& value) { return value.empty() ? std::string("an empty value is not allowed") : std::string(); },
      "", "NON_EMPTY");
  // strtod reads 1e-400 as 0 (with ERANGE, which CLI11 does not look at): --alpha 1e-400 solved at
  // α = 0 without a word. A number whose digits are not all zero and that reads as 0 is refused.
  const CLI::Validator representable(
      [](std::string& value) {
        char* end = nullptr;
        if (std::strtod(value.c_str(), &end) != 0 || end != value.c_str() + value.size() || zero_digits(value))
          return std::string();
        return "'" + value + "' is below the smallest double and would be read as 0";
      },
      "", "REPRESENTABLE");
  // strtod reads hexadecimal too: --alpha 0x10 solved at α = 16, where the JSON and Matrix Market
  // readers refuse '0x10' as no decimal number (and CLI11's integers read 0x5 as 5).
  // Only a 0x prefix is hexadecimal; any other x ('0.1x') is left to CLI11's conversion, which says
  // the value is no number. The prefix is looked for after the white space and signs that
  // strtod/strtoll skip (' 0x10' was read as 16).
  const auto digits_at = [](const std::string& value) { return value.find_first_not_of(" \t\n\v\f\r+-"); };
  const CLI::Validator decimal(
      [digits_at](std::string& value) {
        const std::size_t digits = digits_at(value);
        const bool hexadecimal = digits != std::string::npos && value.size() > digits + 1 && value[digits] == '0' &&
                                 (value[digits + 1] == 'x' || value[digits + 1] == 'X');
        return hexadecimal ? "'" + value + "' is not a decimal number (hexadecimal is not read)" : std::string();
      },
      "", "DECIMAL");
  // CLI11 reads integers with strtoll in base 0: --count 010 was 8 (octal).
  const CLI::Validator no_octal(
      [digits_at](std::string& value) {
        const std::size_t digits = digits_at(value);
        const bool octal = digits != std::string::npos && value.size() > digits + 1 && value[digits] == '0' &&
                           std::isdigit(static_cast<unsigned char>(value[digits + 1]));
        return octal ? "'" + value + "' has a leading zero, which would be read as octal (write it without)"
                     : std::string();
      },
      "", "NO_OCTAL");
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_size_max() > 0) option->check(non_empty);
    const std::string type = option->get_type_name();
    if (type.rfind("FLOAT", 0) == 0) option->check(decimal)->check(representable);
    if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0)
      option->check(decimal)->check(no_octal);  // (CLI11 reads 0x5 as 5 and 010 as 8)
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) refuse_empty_values(*sub);
}

}  // namespace

int run(int argc, char** argv) {
  CLI::App app{
      "coons — discrete Coons patches: fill a Bézier control net from its boundary "
      "(Farin & Hansford, CAGD 16, 1999)",
      "coons"};
  app.set_version_flag("--version", COONS_VERSION);
  app.require_subcommand(1);
  app.footer(
      "\nExample:\n  coons solve data/boundaries/dome.json --alpha -0.2\n"
      "Every command has --help with an example; docs/formats.md is the contract.");

  Registry registry;
  for (int a = 0; a < argc; ++a) registry.command_line += (a ? " " : "") + std::string(a ? argv[a] : "coons");
  register_solve(app, registry);
  register_solvers(app, registry);
  register_export(app, registry);
  register_batch(app, registry);
  register_search_alpha(app, registry);
  register_sweep(app, registry);
  register_refit(app, registry);
  register_study(app, registry);
  register_surface(app, registry);
  register_join(app, registry);
  register_bench_matrix(app, registry);
  register_degree_limit(app, registry);
  register_view(app, registry);
  register_import_step(app, registry);
  refuse_empty_values(app);

  // An unknown command is named (CLI11 would only say that an argument was not expected).
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    for (const auto& e : registry.entries) known = known || e.command->get_name() == argv[1];
    if (!known)
      return fail(kExitBadInput, "command line: unknown command '" + std::string(argv[1]) + "' (see coons --help)");
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::Success& e) {  // --version
    return app.exit(e);
  } catch (const CLI::ConversionError& e) {
    // CLI11 says "Could not convert: --max-iterations = 99999999999": the option as the field, as
    // every other error line has it
    const std::string what = e.what(), prefix = "Could not convert: ", separator = " = ";
    const std::size_t at = what.find(separator);
    if (what.rfind(prefix, 0) == 0 && at != std::string::npos) {
      const std::string option = what.substr(prefix.size(), at - prefix.size());
      std::string type;  // the option's type as its --help shows it (INT, FLOAT, ...)
      for (const CLI::App* command : app.get_subcommands({})) {
        if (const CLI::Option* o = command->get_option_no_throw(option); o && *command) type = o->get_type_name();
      }
      const std::string expected = type.rfind("INT", 0) == 0     ? "an integer from -2147483648 to 2147483647"
                                   : type.rfind("FLOAT", 0) == 0 ? "a number"
                                                                 : "a value this option takes";
      return fail(kExitBadInput, "command line: " + option + ": '" + what.substr(at + separator.size()) + "' is not " +
                                     expected + " (see coons --help)");
    }
    return fail(kExitBadInput, std::string("command line: ") + what + " (see coons --help)");
  } catch (const CLI::ParseError& e) {
    return fail(kExitBadInput, std::string("command line: ") + e.what() + " (see coons --help)");
  }

  // Every exception ends here, after the command's OutputSet (if any) has removed what it started.
  try {
    for (const auto& e : registry.entries)
      if (*e.command) return e.run();
  } catch (const InputError& e) {
    return fail(kExitBadInput, e.what());
  } catch (const nlohmann::json::exception& e) {
    return fail(kExitBadInput, std::string("input: JSON: ") + e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    const std::string path = e.path1().empty() ? "file system" : e.path1().string();
    return fail(kExitBadInput, path + ": " + e.code().message());
  } catch (const std::bad_alloc&) {
    return fail(kExitInternal, "internal: out of memory (see --max-memory)");
  } catch (const std::exception& e) {
    return fail(kExitInternal, std::string("internal: ") + e.what());
  } catch (...) {
    return fail(kExitInternal, "internal: unknown exception");
  }
  return fail(kExitBadInput, "command line: no command given (see coons --help)");
}

}  // namespace coons::cli
