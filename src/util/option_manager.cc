#include "util/option_manager.h"

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>

#include "util/error.h"
#include "util/option_check.h"
#include "util/project_file.h"
#include "util/string.h"

namespace colmap_gcn {

namespace po = boost::program_options;

OptionManager::OptionManager(const std::string& command,
                             const std::string& summary)
    : command_(command),
      summary_(summary),
      desc_(std::make_unique<po::options_description>("Options")) {
  desc_->add_options()("help,h", "Print this help and exit.");
  desc_->add_options()("project_path",
                       po::value<std::string>(),
                       "ini file of options (key=value lines, [Section] "
                       "headers for Section.key); the command line wins");
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

bool OptionManager::IsPassedThrough(const std::string& name) const {
  for (const auto& prefix : pass_through_prefixes_) {
    if (StringStartsWith(name, prefix)) return true;
  }
  return false;
}

void OptionManager::AppendProjectFile(std::vector<std::string>* args) const {
  const std::string path = FindArgument(*args, "project_path");
  if (path.empty()) return;
  // The options given on the command line (abbreviations resolved) win.
  std::set<std::string> given;
  for (const std::string& arg : *args) {
    if (!StringStartsWith(arg, "--")) continue;
    const std::string name = arg.substr(2, arg.find('=') - 2);
    const po::option_description* option = nullptr;
    try {
      option = desc_->find_nothrow(name, /*approx=*/true);
    } catch (const po::error&) {
    }
    given.insert(option != nullptr ? option->long_name() : name);
  }
  for (const ProjectFileOption& option : ReadProjectFile(path)) {
    const bool ours = option.name != "help" && option.name != "project_path" &&
                      desc_->find_nothrow(option.name, false) != nullptr;
    if (!ours && !IsPassedThrough(option.name)) {
      ThrowError(path,
                 ":",
                 option.line,
                 ": unknown option ",
                 option.name,
                 " for colmap ",
                 command_,
                 " (see colmap ",
                 command_,
                 " -h)");
    }
    if (given.count(option.name) > 0) continue;
    args->push_back("--" + option.name);
    args->push_back(option.value);
  }
}

bool OptionManager::Parse(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  AppendProjectFile(&args);
  // Split off the pass-through options first: boost would reject them.
  std::vector<std::string> ours;
  pass_through_.clear();
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    // A COLMAP option a command binds itself (typed, checked once here) is
    // ours although its prefix is passed through.
    const bool bound = StringStartsWith(arg, "--") &&
                       desc_->find_nothrow(arg.substr(2, arg.find('=') - 2),
                                           /*approx=*/false) != nullptr;
    bool passed = false;
    for (const auto& prefix : pass_through_prefixes_) {
      if (!bound && StringStartsWith(arg, "--" + prefix)) {
        pass_through_.push_back(arg);
        if (arg.find('=') == std::string::npos && i + 1 < args.size()) {
          pass_through_.push_back(args[++i]);
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
