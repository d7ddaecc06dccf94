#include "util/option_manager.h"

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "util/error.h"
#include "util/option_check.h"
#include "util/string.h"

namespace colmap_gcn {

namespace po = boost::program_options;

OptionManager::OptionManager(const std::string& command,
                             const std::string& summary)
    : command_(command),
      summary_(summary),
      desc_(std::make_unique<po::options_description>("Options")) {
  desc_->add_options()("help,h", "Print this help and exit.");
}

void OptionManager::AddPassThroughPrefix(const std::string& prefix) {
  pass_through_prefixes_.push_back(prefix);
}

std::string OptionManager::Help() const {
  std::ostringstream help;
  help << "Usage: colmap " << command_ << " [options]\n\n"
       << summary_ << "\n\n"
       << *desc_;
  for (const auto& prefix : pass_through_prefixes_) {
    help << "  --" << prefix << "*  passed on to COLMAP unchanged\n";
  }
  return help.str();
}

bool OptionManager::Parse(int argc, char** argv) {
  // Split off the pass-through options first: boost would reject them.
  std::vector<std::string> ours;
  pass_through_.clear();
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    bool passed = false;
    for (const auto& prefix : pass_through_prefixes_) {
      if (StringStartsWith(arg, "--" + prefix)) {
        pass_through_.push_back(arg);
        if (arg.find('=') == std::string::npos && i + 1 < argc) {
          pass_through_.push_back(argv[++i]);
        }
        passed = true;
        break;
      }
    }
    if (!passed) {
      ours.push_back(arg);
    }
  }

  po::variables_map vmap;
  given_.clear();
  try {
    const po::parsed_options parsed =
        po::command_line_parser(ours).options(*desc_).run();
    po::store(parsed, vmap);
    if (vmap.count("help") > 0) {
      std::cout << Help() << std::flush;
      return false;
    }
    po::notify(vmap);
    for (const auto& option : parsed.options) {
      given_[option.string_key] = StringJoin(option.value, " ");
    }
    for (const auto& step : after_parse_) step(vmap);
  } catch (const po::error& error) {
    ThrowError("colmap ",
               command_,
               ": ",
               error.what(),
               " (see colmap ",
               command_,
               " -h)");
  }
  return true;
}

void OptionManager::Check(const std::function<void()>& check) const {
  try {
    check();
  } catch (const OptionError& error) {
    const std::string flag = FlagName(error.Field());
    if (flag.empty()) throw;
    throw Error(error.MessageFor(flag));
  }
}

bool OptionManager::IsGiven(const std::string& name) const {
  return given_.count(name) > 0;
}

std::string OptionManager::GivenValue(const std::string& name) const {
  const auto it = given_.find(name);
  return it == given_.end() ? "" : it->second;
}

std::string OptionManager::FlagName(const void* field) const {
  for (const auto& [address, flag] : flags_) {
    if (address == field) return flag;
  }
  return "";
}

int IntArgument(const std::vector<std::string>& args,
                const std::string& name,
                int default_value) {
  const std::string option = "--" + name;
  for (size_t i = 0; i < args.size(); ++i) {
    std::string value;
    if (args[i] == option) {
      if (i + 1 >= args.size()) ThrowError(option, " has no value");
      value = args[i + 1];
    } else if (StringStartsWith(args[i], option + "=")) {
      value = args[i].substr(option.size() + 1);
    } else {
      continue;
    }
    const std::string trimmed = StringTrim(value);
    char* end = nullptr;
    errno = 0;
    const long parsed = std::strtol(trimmed.c_str(), &end, 10);
    if (trimmed.empty() || *end != '\0' || errno == ERANGE ||
        parsed < INT_MIN || parsed > INT_MAX) {
      ThrowError(option, " must be an integer (got \"", value, "\")");
    }
    return static_cast<int>(parsed);
  }
  return default_value;
}

bool HasArgument(const std::vector<std::string>& args,
                 const std::string& name) {
  const std::string option = "--" + name;
  for (const std::string& arg : args) {
    if (arg == option || StringStartsWith(arg, option + "=")) return true;
  }
  return false;
}

std::vector<std::string> ArgumentsWithPrefix(
    const std::vector<std::string>& args,
    const std::vector<std::string>& prefixes) {
  std::vector<std::string> selected;
  for (size_t i = 0; i < args.size(); ++i) {
    bool match = false;
    for (const auto& prefix : prefixes) {
      match = match || StringStartsWith(args[i], "--" + prefix);
    }
    const bool has_value = args[i].find('=') == std::string::npos &&
                           i + 1 < args.size() &&
                           !StringStartsWith(args[i + 1], "--");
    if (match) {
      selected.push_back(args[i]);
      if (has_value) selected.push_back(args[i + 1]);
    }
    if (has_value) ++i;
  }
  return selected;
}

}  // namespace colmap_gcn
