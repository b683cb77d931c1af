#include "tool_resampling.h"

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/io/cloud_stream_writer.h>
#include <pcl_sparse/io/scan_cloud.h>

#include <pcl/common/common.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <memory>
#include <vector>

namespace pcl_sparse
{
  namespace tools
  {
    namespace
    {
      /// Whether a cloud in the local frame at \a origin, with bounds \a lo .. \a hi (\a empty: none),
      /// is written with double x y z = origin + point; otherwise floats, moved to the model's frame.
      template <typename PointT>
      bool
      doublePositions (const Eigen::Vector3d& origin, bool empty, const PointT& lo, const PointT& hi)
      {
        // Double x y z only where floats would lose the cloud's resolution (map coordinates): PCL's own
        // loader reads a PCD with double x y z into PointXYZ as zeros, so a mesh merely off the origin
        // (fandisk-large sits at y = 15, 5 extents away) gets float coordinates in its own frame.
        const double extent = empty ? 0.0 : (hi.getVector3fMap () - lo.getVector3fMap ()).maxCoeff ();
        const double largest = origin.cwiseAbs ().maxCoeff () +
                               hi.getVector3fMap ().cwiseAbs ().cwiseMax (lo.getVector3fMap ().cwiseAbs ()).maxCoeff ();
        // A float's spacing at |c| is about 1.2e-7 |c|: within 16 extents it is at most 2e-6 of the extent.
        return !origin.isZero (0.0) && (!(extent > 0.0) || largest > 16.0 * extent);
      }

      /// \a cloud moved by \a origin, in float (the points of a float file in the model's frame).
      template <typename PointT>
      void
      moveToWorld (const pcl::PointCloud<PointT>& cloud, const Eigen::Vector3d& origin, pcl::PointCloud<PointT>& world)
      {
        world = cloud;
        for (PointT& p : world)
          p.getVector3fMap () = (p.getVector3fMap ().template cast<double> () + origin).template cast<float> ();
      }

      /// The local frame a model is resampled in: localFrameOrigin of its seeds (0 unless it lies far from
      /// the origin for its size).
      Eigen::Vector3d
      modelFrameOrigin (const SparseSurfaceModel& model)
      {
        std::vector<Eigen::Vector3d> seeds;
        seeds.reserve (model.patches.size ());
        for (const PatchCode& patch : model.patches)
          seeds.push_back (patch.origin);
        return localFrameOrigin (seeds);
      }

      /// Sets the model of \a resampling, moved to the local frame at \a origin.
      template <typename PointT>
      void
      setLocalModel (SparseSurfaceResampling<PointT>& resampling, const SparseSurfaceModel::ConstPtr& model,
                     const Eigen::Vector3d& origin)
      {
        if (origin.isZero (0.0))
          resampling.setInputModel (model);
        else
        {
          auto moved = std::make_shared<SparseSurfaceModel> (*model);
          moved->translate (-origin);
          resampling.setInputModel (moved);
        }
      }
    } // namespace

    template <typename PointT>
    LocalCloud<PointT>
    resampleInLocalFrame (SparseSurfaceResampling<PointT>& resampling, const SparseSurfaceModel::ConstPtr& model)
    {
      return resampleInLocalFrame (resampling, model, modelFrameOrigin (*model));
    }

    template <typename PointT>
    LocalCloud<PointT>
    resampleInLocalFrame (SparseSurfaceResampling<PointT>& resampling, const SparseSurfaceModel::ConstPtr& model,
                          const Eigen::Vector3d& origin)
    {
      LocalCloud<PointT> local;
      local.origin = origin;
      setLocalModel (resampling, model, origin);
      resampling.compute (local.cloud);
      return local;
    }

    template <typename PointT>
    void
    saveLocalCloud (const std::string& path, const LocalCloud<PointT>& local, bool binary)
    {
      PointT lo, hi;
      if (!local.cloud.empty ())
        pcl::getMinMax3D (local.cloud, lo, hi);
      if (local.origin.isZero (0.0) || doublePositions (local.origin, local.cloud.empty (), lo, hi))
      {
        savePointNormalCloud (path, local.cloud, binary, local.origin);
        removeIfRunFails (path);
        return;
      }
      pcl::PointCloud<PointT> world;
      moveToWorld (local.cloud, local.origin, world);
      savePointNormalCloud (path, world, binary);
      removeIfRunFails (path);
    }

    namespace
    {
      /// -block's points: enough for blocks to pay for themselves, few enough for 200 bytes a point in memory.
      const Range kBlockPoints = Range::closed (4096, 1 << 26);
    } // namespace

    bool
    chooseStreaming (const CommandLine& args, const std::string& output, bool binary, bool png)
    {
      int block = 0;  // read here too, so that a bad -block is refused before any work (it was after encoding)
      args.integer ("-block", block, kBlockPoints);
      const std::string mode = args.value ("-stream", "auto");
      if (mode != "auto" && mode != "on" && mode != "off")
        throw Error ("option -stream: '" + mode + "' is not auto, on or off");
      const bool possible = PointNormalStreamWriter::supports (output, binary) && !png;
      const std::string whole = png ? "-png needs the whole cloud" : "an ascii .pcd is written whole (use .ply or binary)";
      if (mode == "on" && !possible)
        throw Error ("option -stream on: " + whole);
      if (args.has ("-block") && !(mode != "off" && possible))  // it did nothing, without a word
        throw Error ("option -block sets the blocks of a streamed cloud; " + (mode == "off" ? "-stream off writes it whole" : whole));
      return mode != "off" && possible;
    }

    HelpLine
    maxSlopeHelpLine ()
    {
      return {"-max-slope DEG", format ("patches sample only where their code is within DEG degrees of their normal "
                                        "(default %g; 90: no bound)", PatchOwnershipOptions ().max_slope_angle)};
    }

    HelpLine
    clearanceHelpLine ()
    {
      const PatchOwnershipOptions defaults;
      return {"-clearance C", format ("knife edges: no point within C (smaller) patch radii under the other side, max(C, %g) "
                                      "over it (default %g; 0: none)",
                                      defaults.opposite_outside_clearance, defaults.opposite_clearance)};
    }

    void
    readOwnershipOptions (const CommandLine& args, SparseSurfaceResamplingOptions& options)
    {
      args.number ("-max-slope", options.ownership.max_slope_angle, Range::aboveUpTo (0.0, 90.0));
      args.number ("-clearance", options.ownership.opposite_clearance, Range::atLeast (0.0));
    }

    void
    setStreamBlock (const CommandLine& args, SparseSurfaceResamplingBase& resampling)
    {
      ResamplingStreamOptions options;
      args.integer ("-block", options.block_points, kBlockPoints);
      options.kept_candidate_bytes = 64 * options.block_points;
      resampling.setStreamOptions (options);
    }

    template <typename PointT>
    StreamedCloud
    streamResampledCloud (SparseSurfaceResampling<PointT>& resampling, const SparseSurfaceModel::ConstPtr& model,
                          const std::string& path, bool binary, const Eigen::Vector3d* frame_origin)
    {
      if (!PointNormalStreamWriter::supports (path, binary))
        throw Error (path + ": a streamed cloud is written as .pcd (binary) or .ply");
      StreamedCloud result;
      pcl::console::TicToc timer;
      timer.tic ();
      const Eigen::Vector3d origin = frame_origin ? *frame_origin : modelFrameOrigin (*model);
      setLocalModel (resampling, model, origin);
      bool doubles = false;
      if (!origin.isZero (0.0))
      {
        // The bounds of the whole cloud, from the same points (min and max do not depend on the blocks).
        result.bounds_pass = true;
        bool empty = true;
        PointT lo, hi;
        resampling.compute ([&] (const ResampledBlock<PointT>& block) {
          if (block.cloud.empty ())
            return;
          PointT a, b;
          pcl::getMinMax3D (block.cloud, a, b);
          if (!empty)
          {
            a.getVector3fMap () = a.getVector3fMap ().cwiseMin (lo.getVector3fMap ());
            b.getVector3fMap () = b.getVector3fMap ().cwiseMax (hi.getVector3fMap ());
          }
          lo = a;
          hi = b;
          empty = false;
        });
        doubles = doublePositions (origin, empty, lo, hi);
      }
      std::unique_ptr<PointNormalStreamWriter> writer;
      pcl::PointCloud<PointT> world;
      resampling.compute ([&] (const ResampledBlock<PointT>& block) {
        if (!writer)
          writer = std::make_unique<PointNormalStreamWriter> (path, block.total, binary,
                                                              doubles ? origin : Eigen::Vector3d::Zero (),
                                                              cloudExtraFieldOf<PointT> ());
        if (origin.isZero (0.0) || doubles)
          writer->write (block.cloud);
        else
        {
          moveToWorld (block.cloud, origin, world);
          writer->write (world);
        }
      });
      result.points = writer->written ();
      result.resample_seconds = timer.toc () / 1000.0;
      timer.tic ();
      writer->finish ();
      removeIfRunFails (path);
      result.save_seconds = timer.toc () / 1000.0;
      return result;
    }

    CloudExtraField
    resampledExtraField (const std::vector<AttributeChannelInfo>& channels, bool wanted)
    {
      if (!wanted)
        return CloudExtraField::None;
      auto codes = [&] (AttributeChannel channel) {
        return std::any_of (channels.begin (), channels.end (),
                            [&] (const AttributeChannelInfo& info) { return info.channel == channel; });
      };
      if (codes (AttributeChannel::Red) && codes (AttributeChannel::Green) && codes (AttributeChannel::Blue))
        return CloudExtraField::Colour;
      return codes (AttributeChannel::Intensity) ? CloudExtraField::Intensity : CloudExtraField::None;
    }

    const char*
    extraFieldName (CloudExtraField extra)
    {
      return extra == CloudExtraField::Colour ? "rgb" : extra == CloudExtraField::Intensity ? "intensity" : "none";
    }

    HelpLine
    noAttributesHelpLine ()
    {
      return {"-no-attributes", "write x y z, normal and curvature only, without the colour or intensity"};
    }

#define PCL_SPARSE_INSTANTIATE_TOOL_RESAMPLING(T)                                                                      \
  template LocalCloud<T> resampleInLocalFrame (SparseSurfaceResampling<T>&, const SparseSurfaceModel::ConstPtr&);    \
  template LocalCloud<T> resampleInLocalFrame (SparseSurfaceResampling<T>&, const SparseSurfaceModel::ConstPtr&,     \
                                               const Eigen::Vector3d&);                                              \
  template void saveLocalCloud (const std::string&, const LocalCloud<T>&, bool);                                    \
  template StreamedCloud streamResampledCloud (SparseSurfaceResampling<T>&, const SparseSurfaceModel::ConstPtr&,     \
                                               const std::string&, bool, const Eigen::Vector3d*);
    PCL_SPARSE_INSTANTIATE_TOOL_RESAMPLING (pcl::PointNormal)
    PCL_SPARSE_INSTANTIATE_TOOL_RESAMPLING (pcl::PointXYZRGBNormal)
    PCL_SPARSE_INSTANTIATE_TOOL_RESAMPLING (pcl::PointXYZINormal)
#undef PCL_SPARSE_INSTANTIATE_TOOL_RESAMPLING
  } // namespace tools
} // namespace pcl_sparse
