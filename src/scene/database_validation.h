#pragma once

#include "scene/database.h"

namespace colmap_gcn {

// Throws Error with one line naming the first image (name and id) or camera
// whose rows COLMAP 3.8's matcher or mapper would abort on, instead of
// reporting an error: an image whose camera is not in the cameras table, a
// camera model id COLMAP 3.8 does not know or a params blob that does not
// hold the model's parameters, keypoints or descriptors whose
// shape or blob size is inconsistent, or keypoint and descriptor counts of
// one image that differ. Reads only the small columns (and blob lengths), so
// it is cheap on large databases.
void ValidateDatabaseForColmap(const Database& database);

}  // namespace colmap_gcn
