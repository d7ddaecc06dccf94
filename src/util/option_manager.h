#pragma once

#include <functional>
#include <iomanip>
#include <limits>
#include <list>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <boost/program_options.hpp>

#include "util/option_check.h"

namespace colmap_gcn {

// Command-line options in COLMAP's style (`--database_path D`,
// `--GcnMatching.k1 100`, `-h`), on boost::program_options like COLMAP's own
// OptionManager. Options bind directly to fields of Options structs.
class OptionManager {
 public:
  OptionManager(const std::string& command, const std::string& summary);

  template <typename T>
  void AddRequiredOption(const std::string& name,
                         T* option,
                         const std::string& help = "");
  // A flag may be bound to several fields of the same type (e.g.
  // --GcnMatching.k to the retrieval depth of knn and of vocab_tree): the
  // first binding's default and help are shown, a given value sets all.
  template <typename T>
  void AddDefaultOption(const std::string& name,
                        T* option,
                        const std::string& help = "");

  // A second flag for a field bound with AddDefaultOption (COLMAP's name for
  // an option of ours, e.g. --Mapper.num_threads): sets the field only when
  // given, after the other flags.
  template <typename T>
  void AddAliasOption(const std::string& name,
                      T* option,
                      const std::string& help = "");

  // An enum option typed as one of `names`; a value outside them fails
  // Parse with "--<name> must be one of a|b (got "x")".
  template <typename Enum>
  void AddEnumOption(const std::string& name,
                     Enum* option,
                     const EnumNames<Enum>& names,
                     const std::string& help = "");

  // Options starting with one of these prefixes (e.g. "SiftMatching.") are
  // not ours: they are collected verbatim for passing on to COLMAP, except
  // those bound with Add*Option, which the command reads itself (and passes
  // on to COLMAP from its typed field).
  void AddPassThroughPrefix(const std::string& prefix);
  const std::vector<std::string>& PassThroughArguments() const {
    return pass_through_;
  }

  // Parses argv[1..], then the options of `--project_path file.ini` (in
  // COLMAP's layout, util/project_file.h) that argv does not give. Returns
  // false when help was requested (it has been
  // printed; the command should exit 0). Throws Error on unknown, missing or
  // malformed options.
  bool Parse(int argc, char** argv);

  std::string Help() const;

  // Whether option `name` (without "--") was on the command line, and its
  // value as typed ("" when not given).
  bool IsGiven(const std::string& name) const;
  std::string GivenValue(const std::string& name) const;

  // Runs check (an Options::Check(), called once right after Parse and
  // before any work) and rethrows an OptionError about a member bound to a
  // flag as an Error naming the flag: "--GcnMatching.k1 must be >= 1 (got
  // 0)". Other errors pass unchanged.
  void Check(const std::function<void()>& check) const;

  // "--<name>" of the flag bound to the member at `field`, or "".
  std::string FlagName(const void* field) const;

 private:
  bool IsPassedThrough(const std::string& name) const;
  // Appends the options of the --project_path file not given in args;
  // throws Error "<file>:<line>: unknown option ..." for a key that is
  // neither bound nor under a pass-through prefix.
  void AppendProjectFile(std::vector<std::string>* args) const;

  std::string command_;
  std::string summary_;
  std::unique_ptr<boost::program_options::options_description> desc_;
  std::vector<std::string> required_;
  std::vector<std::string> pass_through_prefixes_;
  std::vector<std::string> pass_through_;
  std::vector<std::pair<const void*, std::string>> flags_;
  // Run after parsing: enum conversions and the extra fields of flags bound
  // more than once.
  std::vector<std::function<void(const boost::program_options::variables_map&)>>
      after_parse_;
  std::list<std::string> enum_texts_;
  std::map<std::string, std::string> given_;
};

// The arguments of `args` (as collected by PassThroughArguments) whose
// option starts with "--<prefix>" for one of the prefixes, with their values:
// splits pass-through options between COLMAP commands.
std::vector<std::string> ArgumentsWithPrefix(
    const std::vector<std::string>& args,
    const std::vector<std::string>& prefixes);

// A default as -h prints it: floating-point values with the digits their
// type holds (0.1, not 0.10000000000000001).
template <typename T>
std::string DefaultText(const T& value) {
  std::ostringstream text;
  if constexpr (std::is_floating_point_v<T>) {
    text << std::setprecision(std::numeric_limits<T>::digits10);
  }
  text << value;
  return text.str();
}

template <typename T>
void OptionManager::AddRequiredOption(const std::string& name,
                                      T* option,
                                      const std::string& help) {
  desc_->add_options()(name.c_str(),
                       boost::program_options::value<T>(option)->required(),
                       help.c_str());
  required_.push_back(name);
  flags_.emplace_back(option, "--" + name);
}

template <typename T>
void OptionManager::AddDefaultOption(const std::string& name,
                                     T* option,
                                     const std::string& help) {
  flags_.emplace_back(option, "--" + name);
  if (desc_->find_nothrow(name, false) != nullptr) {
    after_parse_.push_back(
        [name, option](const boost::program_options::variables_map& vmap) {
          if (vmap.count(name) > 0 && !vmap[name].defaulted()) {
            *option = vmap[name].as<T>();
          }
        });
    return;
  }
  desc_->add_options()(name.c_str(),
                       boost::program_options::value<T>(option)->default_value(
                           *option, DefaultText(*option)),
                       help.c_str());
}

template <typename T>
void OptionManager::AddAliasOption(const std::string& name,
                                   T* option,
                                   const std::string& help) {
  desc_->add_options()(
      name.c_str(), boost::program_options::value<T>(), help.c_str());
  after_parse_.push_back(
      [name, option](const boost::program_options::variables_map& vmap) {
        if (vmap.count(name) > 0) *option = vmap[name].as<T>();
      });
}

template <typename Enum>
void OptionManager::AddEnumOption(const std::string& name,
                                  Enum* option,
                                  const EnumNames<Enum>& names,
                                  const std::string& help) {
  flags_.emplace_back(option, "--" + name);
  if (desc_->find_nothrow(name, false) != nullptr) {
    // Bound before (a flag several structs share): a given value sets this
    // field too.
    after_parse_.push_back(
        [name, option, names](
            const boost::program_options::variables_map& vmap) {
          if (vmap.count(name) > 0 && !vmap[name].defaulted()) {
            *option =
                ParseEnum(names, vmap[name].as<std::string>(), "--" + name);
          }
        });
    return;
  }
  std::string* text = &enum_texts_.emplace_back(EnumName(names, *option));
  const std::string choices = EnumChoices(names);
  desc_->add_options()(
      name.c_str(),
      boost::program_options::value<std::string>(text)->default_value(*text),
      (help.empty() ? choices : help + " (" + choices + ")").c_str());
  after_parse_.push_back([name, option, names, text](
                             const boost::program_options::variables_map&) {
    *option = ParseEnum(names, *text, "--" + name);
  });
}

}  // namespace colmap_gcn
