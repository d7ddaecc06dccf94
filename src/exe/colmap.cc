#include "exe/colmap.h"

#include <unistd.h>

#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "controllers/colmap_runner.h"
#include "exe/gcn_adaptive_simulator.h"
#include "exe/gcn_benchmark.h"
#include "exe/gcn_embedding_trainer.h"
#include "exe/gcn_matcher.h"
#include "exe/gcn_merge_databases.h"
#include "exe/gcn_model_evaluator.h"
#include "exe/gcn_pair_exporter.h"
#include "exe/gcn_pair_filter.h"
#include "exe/gcn_reconstructor.h"
#include "exe/gcn_report.h"
#include "exe/gcn_synth.h"
#include "exe/gcn_train.h"
#include "exe/gcn_vocab_tree_builder.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace colmap_gcn {
namespace {

typedef std::function<int(int, char**)> Command;

std::vector<std::pair<std::string, Command>> OurCommands() {
  std::vector<std::pair<std::string, Command>> commands;
  commands.emplace_back("gcn_matcher", &RunGcnMatcher);
  commands.emplace_back("gcn_reconstructor", &RunGcnReconstructor);
  commands.emplace_back("gcn_pair_exporter", &RunGcnPairExporter);
  commands.emplace_back("gcn_report", &RunGcnReport);
  commands.emplace_back("gcn_synth", &RunGcnSynth);
  commands.emplace_back("gcn_train", &RunGcnTrain);
  commands.emplace_back("gcn_model_evaluator", &RunGcnModelEvaluator);
  commands.emplace_back("gcn_embedding_trainer", &RunGcnEmbeddingTrainer);
  commands.emplace_back("gcn_vocab_tree_builder", &RunGcnVocabTreeBuilder);
  commands.emplace_back("gcn_benchmark", &RunGcnBenchmark);
  commands.emplace_back("gcn_adaptive_simulator", &RunGcnAdaptiveSimulator);
  commands.emplace_back("gcn_merge_databases", &RunGcnMergeDatabases);
  commands.emplace_back("gcn_pair_filter", &RunGcnPairFilter);
  return commands;
}

// Replaces this process with the real COLMAP: arguments, output and exit
// code are exactly COLMAP's.
int ExecRealColmap(int argc, char** argv) {
  const std::string exe = FindColmapExecutable();
  std::vector<char*> args(argv, argv + argc);
  args[0] = const_cast<char*>(exe.c_str());
  args.push_back(nullptr);
  execv(exe.c_str(), args.data());
  ThrowError("cannot run ", exe, ": ", std::strerror(errno));
}

int PrintHelp(int argc, char** argv) {
  std::string output;
  RunProcess(FindColmapExecutable(),
             std::vector<std::string>(argv + 1, argv + argc),
             &output);
  std::cout << output << "\ncolmap-gcn " << COLMAP_GCN_VERSION
            << " commands (colmap <command> -h for options):\n";
  for (const auto& command : OurCommands()) {
    std::cout << "  " << command.first << "\n";
  }
  return 0;
}

}  // namespace

std::vector<std::string> GcnCommandNames() {
  std::vector<std::string> names;
  for (const auto& command : OurCommands()) names.push_back(command.first);
  return names;
}

int RunColmapFrontend(int argc, char** argv) {
  try {
    const std::string command = argc > 1 ? argv[1] : "help";
    for (const auto& [name, run] : OurCommands()) {
      if (command == name) {
        InstallInterruptHandlers();
        // Commands see argv without the program name, like COLMAP's.
        return run(argc - 1, argv + 1);
      }
    }
    if (command == "help" || command == "-h" || command == "--help") {
      return PrintHelp(argc, argv);
    }
    return ExecRealColmap(argc, argv);
  } catch (const std::exception& error) {
    std::cerr << "ERROR: " << error.what() << std::endl;
    // Interrupted runs exit as a shell reports a signal (130 for Ctrl-C).
    return PendingInterrupt() != 0 ? 128 + PendingInterrupt() : 1;
  }
}

}  // namespace colmap_gcn
