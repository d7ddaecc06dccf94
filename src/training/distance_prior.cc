#include "training/distance_prior.h"

#include "util/error.h"

namespace colmap_gcn {

void InitializeDistancePrior(GcnModel* model, float other_scale) {
  const GcnShape& shape = model->shape;
  const int d = model->DifferenceDim();
  if (d == 0) {
    ThrowError(
        "the distance prior needs the embedding differences as node "
        "features, not only ",
        QesStructureFeaturesName(model->structure_features));
  }
  const int num_layers = shape.NumGcnLayers();
  bool fits = num_layers >= 2 && shape.gcn_dims[0] >= 2 * d &&
              shape.fc_dim >= num_layers;
  for (int l = 1; l < num_layers; ++l) fits &= shape.gcn_dims[l] > l;
  if (!fits) {
    ThrowError(
        "the distance prior needs >= 2 graph convolutions, a first "
        "layer of >= 2 x ",
        d,
        " units, layer l with > l units and fc_dim >= ",
        num_layers);
  }
  GcnParameters<float>& params = model->params;
  for (float& value : params.Values()) value *= other_scale;
  for (int l = 0; l < num_layers; ++l) params.GcnBias(l).setZero();
  params.Fc1Bias().setZero();
  params.Fc2Bias() = 0.f;

  // Layer 1: units [0, D) = relu(x), [D, 2D) = relu(-x).
  {
    auto w = params.GcnWeight(0);  // rows: [self | aggregated] inputs
    w.leftCols(2 * d).setZero();
    for (int j = 0; j < d; ++j) {
      w(j, j) = 1.f;
      w(j, d + j) = -1.f;
    }
  }
  // Structured units only feed structured units: clear their rows (self and
  // aggregated) and columns, then set the few weights they need.
  auto clear = [](auto* w, int in, int structured_in, int structured_out) {
    w->leftCols(structured_out).setZero();
    w->topRows(structured_in).setZero();
    w->middleRows(in, structured_in).setZero();
  };
  // Layer 2: unit 0 = d (mean of |x|), unit 1 = G d.
  {
    const int in = shape.gcn_dims[0];
    auto w = params.GcnWeight(1);
    clear(&w, in, 2 * d, 2);
    for (int j = 0; j < 2 * d; ++j) {
      w(j, 0) = 1.f / d;
      w(in + j, 1) = 1.f / d;
    }
  }
  // Layer l >= 3: pass units [0, l) on, unit l = G (unit l - 1).
  for (int l = 2; l < num_layers; ++l) {
    const int in = shape.gcn_dims[l - 1];
    auto w = params.GcnWeight(l);
    clear(&w, in, l, l + 1);
    for (int j = 0; j < l; ++j) w(j, j) = 1.f;
    w(in + l - 1, l) = 1.f;
  }
  // FC1 passes the L structured units; FC2 sums them with weight -1.
  {
    auto w = params.Fc1Weight();
    w.leftCols(num_layers).setZero();
    w.topRows(num_layers).setZero();
    for (int j = 0; j < num_layers; ++j) w(j, j) = 1.f;
  }
  params.Fc2Weight().setZero();
  params.Fc2Weight().head(num_layers).setConstant(-1.f);
}

}  // namespace colmap_gcn
