#pragma once

#include <string>
#include <vector>

#include "evaluation/labels.h"
#include "pairing/pairs_io.h"

namespace colmap_gcn {

// The view graph of one method as an N x N adjacency image (images in name
// order), like the paper's Fig. 5. Upper triangle: the method's pairs --
// verified and matchable green, verified but below the label thresholds
// olive, verified although the images share nothing (wrong) red, attempted
// but not verified light grey, verified but hidden from the mapper by the
// look-alike filter purple. Lower triangle: the labels -- matchable
// pairs dark grey, so missed pairs stand out against the upper triangle.
// With a title, counts, labelled axes and a legend of every colour. Written
// as PNG; throws Error if it cannot be written.
void WriteViewGraphImage(const std::string& path,
                         const std::vector<std::string>& image_names,
                         const std::vector<ImageNamePair>& attempted,
                         const std::vector<ImageNamePair>& verified,
                         const std::vector<ImageNamePair>& hidden,
                         const PairLabels& labels,
                         const PairLabelOptions& label_options,
                         const std::string& title = "");

// One precision/recall curve against k per method family.
struct PrecisionRecallSeries {
  std::string name;  // "knn", "vocab_tree"
  std::vector<int> k;
  std::vector<double> precision;
  std::vector<double> recall;
};

// Precision (solid) and recall (dashed) against k, one colour per series,
// plus horizontal reference lines for methods without k (e.g. gcn, oracle:
// name, precision, recall). Written as PNG.
void WritePrecisionRecallPlot(
    const std::string& path,
    const std::string& title,
    const std::vector<PrecisionRecallSeries>& series,
    const std::vector<std::pair<std::string, std::pair<double, double>>>&
        references);

// Curves with values in [0, 1] against a linear x axis (ticks at x), e.g.
// precision / recall / F against a parameter (the paper's Fig. 7).
struct LinePlotSeries {
  std::string name;
  std::vector<double> y;  // one per x
  bool dashed = false;
};
void WriteLinePlot(const std::string& path,
                   const std::string& title,
                   const std::string& x_label,
                   const std::vector<double>& x,
                   const std::vector<LinePlotSeries>& series,
                   const std::string& y_label = "value");

}  // namespace colmap_gcn
