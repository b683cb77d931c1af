#include "tool_resampling.h"

#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/scan_cloud.h>

#include <pcl/common/common.h>

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
      return resampleInLocalFrame (resampling, model, localFrameOrigin (seeds));
    }

    LocalCloud
    resampleInLocalFrame (SparseSurfaceResampling<pcl::PointNormal>& resampling, const SparseSurfaceModel::ConstPtr& model,
                          const Eigen::Vector3d& origin)
    {
      LocalCloud local;
      local.origin = origin;
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
      // Double x y z only where floats would lose the cloud's resolution (map coordinates): PCL's own
      // loader reads a PCD with double x y z into PointXYZ as zeros, so a mesh merely off the origin
      // (fandisk-large sits at y = 15, 5 extents away) gets float coordinates in its own frame.
      pcl::PointNormal lo, hi;
      if (!local.cloud.empty ())
        pcl::getMinMax3D (local.cloud, lo, hi);
      const double extent = local.cloud.empty () ? 0.0 : (hi.getVector3fMap () - lo.getVector3fMap ()).maxCoeff ();
      const double largest = local.origin.cwiseAbs ().maxCoeff () +
                             hi.getVector3fMap ().cwiseAbs ().cwiseMax (lo.getVector3fMap ().cwiseAbs ()).maxCoeff ();
      // A float's spacing at |c| is about 1.2e-7 |c|: within 16 extents it is at most 2e-6 of the extent.
      if (local.origin.isZero (0.0) || !(extent > 0.0) || largest > 16.0 * extent)
      {
        savePointNormalCloud (path, local.cloud, binary, local.origin);
        return;
      }
      pcl::PointCloud<pcl::PointNormal> world = local.cloud;
      for (pcl::PointNormal& p : world)
        p.getVector3fMap () = (p.getVector3fMap ().cast<double> () + local.origin).cast<float> ();
      savePointNormalCloud (path, world, binary);
    }
  } // namespace tools
} // namespace pcl_sparse
