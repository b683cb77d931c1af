#pragma once
/// \file tiled_model.h
/// Moved to pcl_sparse/model/tiled_model.h on 2026-12-02 (the file format reads and writes tiled models, and the
/// format may not include tiles/, which includes the encoder). Kept so that code written before still
/// builds; include the new path.

#include <pcl_sparse/model/tiled_model.h>
