#include <pcl_sparse/patches/patch_options.h>

#include <pcl_sparse/common/error.h>

namespace pcl_sparse
{
  void
  PatchOptions::validate () const
  {
    auto fail = [] (const std::string& field, double value, const std::string& range) {
      throwOutOfRange ("PatchOptions", field, value, range);
    };
    if (!(delta > 0.0 && delta <= M_PI))
      fail ("delta", delta, "0 < delta <= pi");
    if (!(lidar_delta >= 0.0 && lidar_delta <= M_PI))
      fail ("lidar_delta", lidar_delta, "0 <= lidar_delta <= pi");
    if (!(cone_angle > 0.0 && cone_angle <= M_PI))
      fail ("cone_angle", cone_angle, "0 < cone_angle <= pi");
    if (!(eta >= 1.0) || !std::isfinite (eta))
      fail ("eta", eta, "eta >= 1, finite");
    if (!(rho >= 0.0) || !std::isfinite (rho))
      fail ("rho", rho, "rho >= 0, finite");
    if (!(sigma >= 0.0) || !std::isfinite (sigma))
      fail ("sigma", sigma, "sigma >= 0, finite");
    if (max_fruitless_seeds < -1)
      fail ("max_fruitless_seeds", max_fruitless_seeds, "max_fruitless_seeds >= -1");
    if (!(tail_pruning_after == -1.0 || (tail_pruning_after >= 0.0 && tail_pruning_after <= 1.0)))
      fail ("tail_pruning_after", tail_pruning_after, "-1 (by surface) or 0 <= tail_pruning_after <= 1");
    if (cover_unreferenced_vertices < -1 || cover_unreferenced_vertices > 1)
      fail ("cover_unreferenced_vertices", cover_unreferenced_vertices, "-1 (by surface), 0 or 1");
    if (!(unreferenced_patch_spacings >= 0.0) || !std::isfinite (unreferenced_patch_spacings))
      fail ("unreferenced_patch_spacings", unreferenced_patch_spacings, "unreferenced_patch_spacings >= 0, finite");
    if (max_patch_vertices < -1)
      fail ("max_patch_vertices", max_patch_vertices, "max_patch_vertices >= -1");
    if (min_growth_vertices < 0)
      fail ("min_growth_vertices", min_growth_vertices, "min_growth_vertices >= 0");
    if (!(steep_frame_angle == -1.0 || (steep_frame_angle >= 0.0 && steep_frame_angle <= M_PI / 2.0)))
      fail ("steep_frame_angle", steep_frame_angle, "-1 (by surface) or 0 <= steep_frame_angle <= pi / 2");
    if (!(face_steep_frame_angle >= 0.0 && face_steep_frame_angle <= M_PI / 2.0))
      fail ("face_steep_frame_angle", face_steep_frame_angle, "0 <= face_steep_frame_angle <= pi / 2");
    if (!(hidden_triangle_gap == -1.0 || hidden_triangle_gap >= 0.0) || !std::isfinite (hidden_triangle_gap))
      fail ("hidden_triangle_gap", hidden_triangle_gap, "-1 (by surface) or hidden_triangle_gap >= 0, finite");
    if (merge_own_elements < 0)
      fail ("merge_own_elements", merge_own_elements, "merge_own_elements >= 0");
    if (min_patch_size < 1)
      fail ("min_patch_size", min_patch_size, "min_patch_size >= 1");
  }

  PatchOptions
  paperPatchOptions (PatchOptions base)
  {
    base.cone_angle = M_PI / 2.0;
    base.pairwise_cone = false;
    base.complete_faces = false;
    base.seed_patches_on_faces = false;
    base.hidden_triangle_gap = 0.0;
    base.face_steep_frame_angle = 0.0;
    base.drop_redundant_patches = false;
    base.merge_own_elements = 0;
    base.lidar_delta = 0.0;
    return base;
  }

  PatchOptions
  authorsCodePatchOptions (PatchOptions base)
  {
    base = paperPatchOptions (base);
    base.cone_angle = M_PI / 2.5;
    base.cover_all_vertices = false;
    base.cover_unreferenced_vertices = 0;
    return base;
  }
} // namespace pcl_sparse
