#pragma once
/// \file tile_grid.h
/// Moved to pcl_sparse/model/tile_grid.h on 2026-12-02 (the file format reads and writes tiled models, and the
/// format may not include tiles/, which includes the encoder). Kept so that code written before still
/// builds; include the new path.

#include <pcl_sparse/model/tile_grid.h>
