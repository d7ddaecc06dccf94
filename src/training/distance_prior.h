#pragma once

#include "gcn/gcn_model.h"

namespace colmap_gcn {

// The "distance prior" initialisation (docs/gcn.md): the network starts as
// the context-aware distance classifier
//   logit(v) = -(d + G d + G^2 d + ... + G^(L-1) d)(v),
//   d(v) = mean_j |x_v - x_q|_j over the D standardised embedding dimensions
//   (structural features start unused),
// with G the model's aggregation (row-normalised: neighbour means) and L
// the number of graph convolutions: layer 1 computes [relu(x), relu(-x)],
// layer 2 the mean (d) and its aggregate (G d), every later layer passes
// these on and adds one more hop; FC1 passes them to FC2, whose weights
// are -1. The other units keep the Xavier weights scaled by other_scale, so
// that training can use them. Why: with few training scenes, SGD from a
// random start fits each scene's embedding directions instead of distances
// (docs/model_card.md); the prior starts from what kNN knows plus
// neighbourhood context. Needs L >= 2, gcn_dims[0] >= 2 D, gcn_dims[l] >
// l for l >= 1 and fc_dim >= L; throws Error otherwise.
void InitializeDistancePrior(GcnModel* model, float other_scale);

}  // namespace colmap_gcn
