#include "training/gcn_training_run.h"

#include "gcn/model_file.h"
#include "util/error.h"
#include "util/timer.h"

namespace colmap_gcn {

GcnTrainingRun RunGcnTraining(const GcnTrainingRunOptions& options) {
  std::vector<std::string> held_out = options.validation_scenes;
  held_out.insert(
      held_out.end(), options.test_scenes.begin(), options.test_scenes.end());
  const std::vector<LabelledScene> train = WithoutHeldOutScenes(
      FindLabelledScenes(options.benchmark_path, options.scenes), held_out);
  if (train.empty()) {
    ThrowError(
        "no training scenes left after holding out validation and "
        "test scenes");
  }
  const std::vector<LabelledScene> validation =
      options.validation_scenes.empty()
          ? std::vector<LabelledScene>()
          : FindLabelledScenes(options.benchmark_path,
                               options.validation_scenes);

  GcnTrainingRun run;
  const Timer timer;
  run.model = TrainGcnModel(train, validation, options.pipeline);
  WriteGcnModel(options.output_path, run.model);
  run.seconds = timer.ElapsedSeconds();
  if (!options.test_scenes.empty()) {
    const int num_threads = options.pipeline.training.num_threads;
    run.test_comparisons = CompareWithFixedK(
        run.model,
        EmbedScenesForModel(
            run.model,
            FindLabelledScenes(options.benchmark_path, options.test_scenes),
            options.pipeline.labels,
            num_threads,
            options.pipeline.cnn.onnx_path,
            options.pipeline.images,
            "--GcnTraining.onnx_path"),
        options.max_fixed_k,
        num_threads);
  }
  return run;
}

}  // namespace colmap_gcn
