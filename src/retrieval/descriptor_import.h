#pragma once

#include <string>
#include <vector>

#include "retrieval/kmeans.h"
#include "retrieval/knn.h"
#include "scene/database.h"

namespace colmap_gcn {

// Global descriptors computed elsewhere (e.g. NetVLAD or another CNN through
// hloc), one named vector per image, as read from disk (not normalised).
struct ImportedDescriptors {
  std::vector<std::string> names;
  FloatMatrix vectors;  // names.size() x D
};

// hloc's global-feature HDF5: one group per image name (a '/' in the name
// nests groups), dataset "global_descriptor" of shape (D,) or (1, D),
// float16/32/64.
ImportedDescriptors ReadHdf5GlobalDescriptors(const std::string& path);

// NumPy .npy (version 1-3, little-endian float16/32/64, C order, 2-D N x D)
// with the image names one per line in "<path>.txt", or else in the same
// path with the extension replaced by ".txt".
ImportedDescriptors ReadNpyGlobalDescriptors(const std::string& path);

// Text: one image per line, "name v1 v2 ... vD"; '#' lines and empty lines
// are skipped.
ImportedDescriptors ReadTextGlobalDescriptors(const std::string& path);

// By extension: .h5/.hdf5, .npy, .txt.
ImportedDescriptors ReadGlobalDescriptors(const std::string& path);

// Rows for the database images (ascending image id, returned in *image_ids),
// L2-normalised. Throws Error listing the database images without a
// descriptor and the file's names that are not database images; names are
// matched exactly, never guessed.
EmbeddingMatrix MatchDescriptorsToImages(
    const ImportedDescriptors& imported,
    const std::vector<DatabaseImage>& images,
    std::vector<image_t>* image_ids);

// IEEE 754 binary16 to float (subnormals, infinities and NaN included).
float HalfToFloat(uint16_t half);

}  // namespace colmap_gcn
