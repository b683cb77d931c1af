#include "tool_resampling.h"

#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/scan_cloud.h>

#include <memory>
#include <vector>

namespace pcl_sparse
{
  namespace tools
  {
    LocalCloud
    resampleInLocalFrame (SparseSurfaceResampling<pcl::PointNormal>& resampling, const SparseSurfaceModel::ConstPtr& model)
    {
      std::vector<Eigen::Vector3d> seeds;
      seeds.reserve (model->patches.size ());
      for (const PatchCode& patch : model->patches)
        seeds.push_back (patch.origin);
      LocalCloud local;
      local.origin = localFrameOrigin (seeds);
      if (local.origin.isZero (0.0))
        resampling.setInputModel (model);
      else
      {
        auto moved = std::make_shared<SparseSurfaceModel> (*model);
        moved->translate (-local.origin);
        resampling.setInputModel (moved);
      }
      resampling.compute (local.cloud);
      return local;
    }

    void
    saveLocalCloud (const std::string& path, const LocalCloud& local, bool binary)
    {
      savePointNormalCloud (path, local.cloud, binary, local.origin);
    }
  } // namespace tools
} // namespace pcl_sparse
