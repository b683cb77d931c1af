/// pcl_sparse_encode: encodes a triangle mesh as a sparse surface model and reports the paper's figures
/// (N_V, M, rho, nnz, RMSE, RMSE / diag, CR) and the seconds per stage.
///
///   pcl_sparse_encode MESH [-rho R] [-f F] [-L N] [-eps E] [-min-samples N] [-cone DEG] [-recon RECON.ply]
///                     [-error ERR.ply] [-o MODEL.psm [-tolerance T] [-footprint-steps R] [--store-vertices]
///                     [--varint-layout] [--exact-footprints]] [-tiles N]
///                     [-memory SIZE] [--json] [-q]
///
/// Under `mpirun -n K` (tools built with MPI) the tiles are shared out over the K processes and rank 0
/// writes the one model file, byte-identical to the run without MPI.

#include "tool_input.h"
#include "tool_processes.h"
#include "tool_render.h"
#include "tool_support.h"
#include "tool_tiled_encoding.h"
#include "tool_tiling.h"

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/color_map.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/common/progress.h>
#include <pcl_sparse/common/thread_count.h>
#include <pcl_sparse/encoder/measured_write_options.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/file_tolerance.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/format/tiled_model_file.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/patches/face_completion.h>
#include <pcl_sparse/tiles/memory_tile_source.h>
#include <pcl_sparse/tiles/spilled_mesh_tile_source.h>
#include <pcl_sparse/tiles/spilled_tile_source.h>
#include <pcl_sparse/tiles/tile_statistics.h>

#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

using namespace pcl_sparse;

namespace
{
  /// The process's peak resident set so far in MB (VmHWM of /proc/self/status; 0 where there is none),
  /// reported by --json at the stage boundaries (bench/encode_bounded.sh).
  double
  peakResidentMb ()
  {
    std::FILE* file = std::fopen ("/proc/self/status", "r");
    if (!file)
      return 0.0;
    char line[256];
    double kb = 0.0;
    while (std::fgets (line, sizeof line, file))
      if (std::sscanf (line, "VmHWM: %lf", &kb) == 1)
        break;
    std::fclose (file);
    return kb / 1024.0;
  }

  const tools::ToolDescription kTool = {
    "pcl_sparse_encode", "IN [options]",
    {
      {"IN", "a triangle mesh (.obj .off .ply .stl) or a scan (.pcd .xyz, .ply of points)"},
      {"-viewpoint X,Y,Z", "scans: the sensor position the normals face (default: the file's VIEWPOINT"},
      {"", "when plausible, else consistently oriented, outward on closed surfaces; tiles too);"},
      {"", "points exactly there are dropped as no-returns (not those at the file's origin)"},
      {"-rho R", "patch size bound A_p / A (default 0.001; paper: 0.005, 0.001, 0.0002)"},
      {"-f F", "Nyquist factor in [0, 1] (default 0.5; 0 = plain OMP)"},
      {"--authors-nyquist", "the authors' cap lambda >= f mu instead of the paper's lambda / 2 > f mu"},
      {"-L N", "atoms per patch at most (default 12)"},
      {"-eps E", "relative residual to stop at, in (0, 1) (default 0.01)"},
      {"-atom-loss A", "leave out the atoms that buy least while the model's squared error grows by at most the"},
      {"", "fraction A, for smaller files (default 0: every code as OMP made it; 0.2: 0-22 % smaller"},
      {"", "default files, up to 20 % farther from the mesh, bench/results/atom_loss.md)"},
      {"-min-samples N", "patches with fewer points get extra samples (default 64; authors 128; at most 100000)"},
      {"-preset P", "default (measured best) or paper (the paper's configuration); the other options"},
      {"", "override it"},
      {"-basis B", "atoms: quadric = dct and x, y, x^2, xy, y^2 (default); dct cos(i pi (x+1)/2) cos(j pi (y+1)/2),"},
      {"", "odd parts too; paper cos(i pi x) cos(j pi y) (-preset paper)"},
      {"-sigma S", "seeds closer than S r_P to a kept patch's seed are not grown (default 0.8, the paper's)"},
      {"-cone DEG", "normal cone of patch growth in degrees, in (0, 180] (default 72, the authors' code's;"},
      {"", "-preset paper 90)"},
      {"-footprint-reach DEG", "meshes: footprints reach DEG along smooth patch borders to their triangles'"},
      {"", "outer corners, in [0, 180] (default 17; 0: clipped at every border)"},
      {"--keep-redundant-patches", "keep the patches whose every vertex and triangle others also hold (default:"},
      {"", "dropped, up to 27 % of the patches of a mesh; -preset paper keeps them)"},
      {"--keep-flipped-places", "meshes: keep the footprints where a code's normal points over 110 degrees away from"},
      {"", "the nearest face (default: drawn in there, so resampling emits no flipped normal; -preset paper keeps"},
      {"", "them; 0.03-1.4 s on 2 threads, bench/results/flips.md)"},
      {"-merge-patches K", "merge each patch with at most K vertices and triangles of its own into its neighbours"},
      {"", "(default 8: up to a third off the file, bench/results/patch_merging.md; 0: none;"},
      {"", "-preset paper 0)"},
      {"-point-patches S", "scans: a point in no triangle gets a patch of its own only farther than S mean edge"},
      {"", "lengths from the triangles (default 3; 0: every such point)"},
      {"-seed S", "seed of the extra samples (default 42)"},
      {"-threads N", "OpenMP threads (default: all; the model does not depend on it)"},
      {"-recon RECON", "write the reconstructed mesh (input vertex order and faces)"},
      {"-error ERR.ply", "write the reconstruction coloured by vertex error, blue (0) to red (max)"},
      {"-o MODEL.psm", "write the model file (docs/FORMAT.md)"},
      {"-tolerance T", "model file: largest surface displacement / bbox diagonal (default: 3 x the model's"},
      {"", "mean error, lower where that is expected to add over 5 % to the distance, with 5-bit footprint"},
      {"", "extents then (derivedWriteOptions); from a mesh, the smallest of that file and a few coarser and"},
      {"", "finer ones whose Chamfer distance to the mesh is within 8 % of the lossless model's, measured"},
      {"", "(measuredWriteOptions: 0.3-3 s more); 0 = lossless)"},
      {"-footprint-steps R", "quantised model file: a patch's footprint keeps 2 opposite angles, and those between where"},
      {"", "the coded ones stray from it by more than R extent levels summed over the angles (default 2, also"},
      {"", "with 5-bit extents: within 10 % of the lossless model's Chamfer distance on the 25 shared meshes;"},
      {"", "0: the 2 everywhere, smaller, far less near)"},
      {"--exact-footprints", "quantised model file: refine footprints against their exact extents, also where"},
      {"", "neighbours hold the places at their borders (1-13 % larger; see ModelWriteOptions::footprint_slack)"},
      {"--store-vertices", "model file: also store the patch vertices (for -recon from the file)"},
      {"--varint-layout", "quantised model file: zstd over varints instead of range-coded fields (up to 22 %"},
      {"", "larger)"},
      {"-tiles N", "tile the input: N tiles along the longest side of its bounding box, each encoded apart"},
      {"", "(docs/TILES.md); -o then writes a tiled model, which -box decodes region by region"},
      {"-memory SIZE", "tile by itself when the untiled encoding would need more (default 2G; K, M, G, T);"},
      {"", "an ascii / binary PCD or binary PLY whose header says so is spilled into tiles on disk, never"},
      {"", "loaded whole (a binary_compressed PCD is loaded whole, with a warning)"},
      {"", "(then -recon, -error and -png are refused)"},
      {"", "under mpirun -n K the tiles are shared out over the K processes (same model file)"},
      tools::pngHelpLine (),
      {"--json", "print one JSON object on stdout instead of the table row"},
      {"-q", "quiet (no progress, only the result and errors)"},
    },
    1,
    {"-rho", "-f", "-L", "-eps", "-atom-loss", "-min-samples", "-sigma", "-cone", "-footprint-reach", "-seed", "-threads", "-basis", "-recon", "-error", "-o", "-tolerance",
     "-footprint-steps", "-viewpoint", "-preset", "-png", "-size", "-view", "-tiles", "-memory", "-merge-patches",
     "-point-patches"},
    {"--json", "-q", "--authors-nyquist", "--store-vertices", "--varint-layout", "--exact-footprints",
     "--keep-redundant-patches", "--keep-flipped-places"}};
} // namespace

int
main (int argc, char** argv)
{
  const tools::ProcessGroup group (argc, argv);
  return group.finish (tools::runTool (argc, argv, kTool, [&] (const tools::CommandLine& args) {
    const bool json = args.has ("--json");
    const bool quiet = args.has ("-q");
    if (quiet || json)
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);  // notes off, as in the other tools
    args.expectPositional (1, "exactly one input");
    tools::checkPngOptions (args);
    const std::string& path = args.positional ().front ();

    SparseSurfaceEncoderOptions options = encoderPresetOptions (encoderPresetFromName (args.value ("-preset", "default")));
    args.number ("-rho", options.patches.rho, tools::Range::aboveUpTo (0.0, 1.0));  // A_p / A: 1 bounds nothing
    // The ranges of SparseSurfaceEncoderOptions::validate, checked here so that a refusal names the option
    // ("option -f: 2 is not in [0, 1]"), not the field it sets ("coding.nyquist_factor = 2").
    args.number ("-f", options.coding.nyquist_factor, tools::Range::closed (0.0, 1.0));
    args.integer ("-L", options.coding.max_atoms, tools::Range::atLeast (1));
    args.number ("-eps", options.coding.tolerance, tools::Range::open (0.0, 1.0));
    args.number ("-atom-loss", options.atom_loss_allowance, tools::Range::closed (0.0, 1e6));
    args.integer ("-min-samples", options.coding.min_samples, tools::Range::closed (0, 100000));
    args.number ("-sigma", options.patches.sigma, tools::Range::atLeast (0.0));
    args.angle ("-cone", options.patches.cone_angle);
    args.number ("-footprint-reach", options.coding.footprint_reach_degrees, tools::Range::closed (0.0, 180.0));
    args.integer ("-seed", options.coding.seed, tools::Range::atLeast (0));
    if (args.has ("--authors-nyquist"))
      options.coding.nyquist_rule = NyquistRule::AuthorsCode;
    if (args.has ("--keep-redundant-patches"))
      options.patches.drop_redundant_patches = false;
    if (args.has ("--keep-flipped-places"))
      options.trim_flipped_places = false;
    args.integer ("-merge-patches", options.patches.merge_own_elements, tools::Range::atLeast (0));
    args.number ("-point-patches", options.patches.unreferenced_patch_spacings, tools::Range::atLeast (0.0));
    if (args.has ("-basis"))
      options.basis = cosineBasisKindFromName (args.value ("-basis"));
    int threads = 0;
    args.integer ("-threads", threads, tools::Range::closed (0, 1024));
    const std::string recon_path = args.value ("-recon");
    const std::string error_path = args.value ("-error");
    const std::string model_path = args.value ("-o");
    ModelWriteOptions write_options;
    const bool tolerance_given = args.number ("-tolerance", write_options.tolerance, tools::Range::closed (0.0, 0.1));
    // A file counts a seed's steps in 32 bits: under about 1.3e-9 of the diagonal they overflow, found only
    // when the file is written, after the whole encoding.
    if (write_options.tolerance > 0.0 && write_options.tolerance < 1e-8)
      throw Error ("option -tolerance: " + shortestDecimal (write_options.tolerance) +
                   " is finer than a file's 32-bit steps count (0 for the lossless file, or 1e-8 to 0.1)");
    const bool steps_given =
      args.number ("-footprint-steps", write_options.footprint_refine_steps, tools::Range::closed (0.0, 1e6));
    write_options.include_vertices = args.has ("--store-vertices");
    write_options.range_coding = !args.has ("--varint-layout");
    write_options.footprint_slack = !args.has ("--exact-footprints");
    if (model_path.empty () && (tolerance_given || steps_given || write_options.include_vertices ||
                                !write_options.range_coding || !write_options.footprint_slack))
      throw Error ("options -tolerance, -footprint-steps, --store-vertices, --varint-layout and --exact-footprints need "
                   "-o MODEL.psm");
    options.validate ();
    Eigen::Vector3d viewpoint;
    const bool has_viewpoint = tools::parseViewpoint (args, viewpoint);
    if (!recon_path.empty () && !isMeshFileExtension (recon_path))
      throw Error ("option -recon: '" + recon_path + "' has no mesh extension (.obj .off .ply .stl)");
    if (!error_path.empty () && !tools::hasExtension (error_path, ".ply"))
      throw Error ("option -error: '" + error_path + "' must end in .ply");
    if (!model_path.empty () && !tools::hasExtension (model_path, ".psm"))
      throw Error ("option -o: '" + model_path + "' must end in .psm");
    tools::checkOutputPaths ({path}, {model_path, recon_path, error_path, args.value ("-png")});

    pcl::console::TicToc timer;
    timer.tic ();
    // A large PCD / PLY is spilled into tiles on disk instead of loaded (docs/TILES.md, "Bounded memory").
    bool spilled_mesh = false;
    std::size_t header_points = 0;
    const bool bounded = tools::spillsInput (args, path, spilled_mesh, header_points);
    const bool needs_input = !recon_path.empty () || !error_path.empty () || args.has ("-png");
    if (bounded && needs_input)
      throw Error (path + ": " + std::to_string (header_points) +
                   " points are more than -memory allows to hold, so it is encoded tile by tile from disk; -recon, "
                   "-error and -png need the whole input in memory: raise -memory to use them");
    tools::SurfaceInput input;
    if (!bounded)
      input = tools::loadSurfaceInput (path, has_viewpoint ? &viewpoint : nullptr);
    tools::refuseViewpointOnMesh (has_viewpoint, bounded ? spilled_mesh : input.mesh != nullptr, path);
    TileGridOptions grid_options;
    const bool tiled = tools::chooseTiling (args, bounded ? header_points : input.points (), grid_options);
    // The whole input's positions, for the untiled statistics and what needs the input (a tiled model is
    // measured tile by tile, from the tile source).
    std::vector<Eigen::Vector3d> input_positions;
    if (!bounded && (!tiled || needs_input))
      input_positions = input.worldPositions ();
    if (tiled && !args.has ("-tiles"))  // tiles sized for the budget, so many side by side at most
      threads = std::min (resolveThreadCount (threads), tools::kBudgetTilesAtOnce);
    if (!tiled && group.rank () != 0)
      return 0;  // an untiled encoding is rank 0's alone
    TileSource::Ptr source;
    if (bounded)
    {
      // Every rank spills its own copy of the input (its own temporary directory), as every rank of the
      // in-memory path loads its own: the same tiles, no shared file system needed.
      SpillOptions spill;
      spill.grid = grid_options;
      if (has_viewpoint)
        spill.cleaning.sensor_position = viewpoint;
      spill.progress = makeConsoleProgress (quiet || json || group.rank () != 0);
      if (spilled_mesh)
      {
        const SpilledMeshTileSource::Ptr mesh_source = spillMeshIntoTiles (path, spill);
        // Each tile would be refused as a soup; loaded whole, its corners are welded (loadSurfaceInput).
        if (mesh_source->isTriangleSoup ())
          throw Error (tools::format ("%s: its faces share no vertex (a triangle soup), and welding its corners at equal "
                                      "positions needs the whole file in memory: raise -memory to %.0fM (its %zu "
                                      "points x 1.5 KB) to load it whole and weld it, or weld the file first",
                                      path.c_str (), std::ceil (static_cast<double> (header_points) * tools::kEncoderBytesPerPoint / 1048576.0),
                                      header_points));
        source = mesh_source;
      }
      else
        source = spillIntoTiles (path, spill);
    }
    else if (tiled)
      source = input.mesh ? std::make_shared<MemoryTileSource> (input.mesh, grid_options)
                          : std::make_shared<MemoryTileSource> (input.scan, grid_options);
    if (source && has_viewpoint)
      source->setViewPoint (viewpoint.x (), viewpoint.y (), viewpoint.z ());
    const double load_seconds = timer.toc () / 1000.0;
    const double peak_after_load = peakResidentMb ();
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    SparseSurfaceModel model;
    TiledModel tiled_model;
    EncoderTimings tiled_timings;
    ModelStatistics tiled_stats;
    FaceCoverage face_coverage;  // untiled: the faces of the surface that are a triangle of no patch
    tools::TiledEncodingReport tiled_report;
    double peak_after_encode = 0.0;
    if (tiled)
    {
      // Every rank encodes its share of the same tiles; rank 0 merges and writes.
      // From the tiles, so that both tile sources give the same figures (and file tolerance); the patches'
      // vertex lists go once measured unless the file or the reconstruction needs them.
      TiledStatisticsOptions statistics_options;
      statistics_options.drop_vertices = !write_options.include_vertices && !needs_input;
      timer.tic ();
      tiled_report =
        tools::encodeTilesAcross (group, *source, options, threads, quiet || json, statistics_options, tiled_model, tiled_stats);
      tiled_timings.total = timer.toc () / 1000.0;
      peak_after_encode = peakResidentMb ();
      tiled_timings.coding = tiled_report.coding;
      tiled_timings.patches = std::numeric_limits<double>::quiet_NaN ();  // tiles time patches and coding as one
      if (group.rank () != 0)
        return 0;
      // Tiles too small to make a surface are left empty: with all of them so, "success" with no patch (or
      // "encodeModel: the model has no basis" with -o), where the untiled encoding coded the input.
      if (tiled_model.model.patches.empty ())
        throw Error (path + ": no tile made a surface, all are too small to code (uncovered points: " +
                     std::to_string (tiled_stats.uncovered) + "): use fewer tiles (-tiles) or none");
      // Each tile's encoder fills its own (fillAttributeGaps); the count comes from reading the input.
      if (const ScanCleaningReport* cleaning = tools::cleaningReportOf (input, source.get ()))
        tools::printIntensityGaps (path, *cleaning);
    }
    else
    {
      tools::setSurfaceInput (encoder, input);
      if (has_viewpoint)
        encoder.setViewPoint (viewpoint.x (), viewpoint.y (), viewpoint.z ());
      encoder.setOptions (options);
      encoder.setNumberOfThreads (threads);
      encoder.setProgressCallback (makeConsoleProgress (quiet || json));
      encoder.compute (model);
      peak_after_encode = peakResidentMb ();
      if (encoder.getDuplicateFaces () > 0)
        tools::printNote (tools::format ("%s: left out %zu repeated faces (the same three vertices as an earlier face)",
                                         path.c_str (), encoder.getDuplicateFaces ()));
      tools::printAttributeGaps (path, encoder.getAttributeGaps ());
      face_coverage = faceCoverage (*encoder.getSurface (), encoder.getPatches ());
      // From 1 % of the area (fandisk has 7 such faces, 0.07 %, which the patches beside them reach over:
      // Patch::beside_uncovered_face); --json gives every count.
      if (input.mesh && face_coverage.area_fraction >= 0.01)
        tools::printNote (tools::format ("%s: %zu faces (%.2f %% of the area) are a triangle of no patch (their normals "
                                         "lie outside every neighbouring patch's cone): resampled clouds may leave them out",
                                         path.c_str (), face_coverage.faces_in_no_patch, 100.0 * face_coverage.area_fraction));
    }

    timer.tic ();
    std::vector<double> errors;
    ModelStatistics stats;
    if (tiled)
    {
      stats = tiled_stats;
      model = std::move (tiled_model.model);
      if (needs_input)
        model.statistics (input_positions, &errors);  // the errors per vertex, for -error and -png
    }
    else
      stats = model.statistics (input_positions, &errors);
    const double statistics_seconds = timer.toc () / 1000.0 + tiled_report.statistics;
    if (!tolerance_given)
    {
      // From the vertex errors where the whole input is here; a tiled model has only its statistics (and the
      // same file whether -recon asked for the errors or not).
      const double steps = write_options.footprint_refine_steps;
      write_options = derivedWriteOptions (stats, tiled ? std::vector<double> () : errors, model.bbox_diagonal, write_options);
      if (steps_given)
        write_options.footprint_refine_steps = steps;
    }

    timer.tic ();
    MeasuredWriteChoice file_choice;
    if (!tolerance_given && !tiled && input.mesh && !model_path.empty () && write_options.tolerance > 0.0)
    {
      // A mesh's default file: the smallest of the bound's file and a few coarser and finer ones that stays
      // within the distance allowed, measured against the mesh (measured_write_options.h). Scans and tiled
      // models keep the bound's file.
      MeasuredWriteOptions measure;
      measure.num_threads = threads;
      if (steps_given)
        for (WriteCandidate& candidate : measure.candidates)
          candidate.refine_steps = write_options.footprint_refine_steps;
      file_choice = measuredWriteOptions (model, *encoder.getSurface (), write_options, measure,
                                          makeConsoleProgress (quiet || json));
      write_options = file_choice.options;
    }
    if (!model_path.empty () && tiled)
    {
      tiled_model.model = std::move (model);
      saveTiledModel (model_path, tiled_model, write_options, threads);
      tools::removeIfRunFails (model_path);
      model = std::move (tiled_model.model);
    }
    else if (!model_path.empty ())
    {
      if (!file_choice.file.empty ())  // the measured file's bytes, as saveModel would encode them again
        writeBytesAtomically (model_path, file_choice.file.data (), file_choice.file.size ());
      else
        saveModel (model_path, model, write_options);
      tools::removeIfRunFails (model_path);
    }
    if (!recon_path.empty () || !error_path.empty () || args.has ("-png"))
    {
      // A scan's reconstruction is its points (its neighbourhood surface is the encoder's, not the file's).
      TriangleMesh reconstructed;
      reconstructed.vertices = input_positions;
      if (input.mesh)
        reconstructed.triangles = input.mesh->triangles;
      const std::vector<Eigen::Vector3d> vertices = model.reconstructVertices (input_positions.size ());
      for (std::size_t v = 0; v < vertices.size (); ++v)
        if (vertices[v].allFinite ())  // vertices in no patch keep their input position
          reconstructed.vertices[v] = vertices[v];
      if (!recon_path.empty ())
      {
        saveTriangleMesh (recon_path, reconstructed);
        tools::removeIfRunFails (recon_path);
      }
      if (!error_path.empty ())
      {
        std::vector<RgbColor> colors (errors.size ());
        for (std::size_t v = 0; v < errors.size (); ++v)
          colors[v] = errorColor (stats.max_error > 0.0 ? errors[v] / stats.max_error : 0.0);
        saveColoredMesh (error_path, reconstructed, colors);
        tools::removeIfRunFails (error_path);
      }
      tools::writeErrorPng (args, reconstructed, errors, model.bbox_diagonal);
    }
    const double write_seconds = timer.toc () / 1000.0;
    const EncoderTimings& t = tiled ? tiled_timings : encoder.getTimings ();

    if (json)
    {
      tools::JsonObject object;
      object.add ("file", path)
        .add ("vertices", stats.num_vertices)
        .add ("faces", input.mesh ? input.mesh->triangles.size () : 0)
        .add ("patches", stats.num_patches)
        .add ("rho", options.patches.rho)
        .add ("nyquist_factor", options.coding.nyquist_factor)
        .add ("basis", cosineBasisKindName (options.basis))
        .add ("max_atoms", options.coding.max_atoms)
        .add ("atom_loss", options.atom_loss_allowance)
        .add ("tolerance", options.coding.tolerance)
        .add ("min_samples", options.coding.min_samples)
        .add ("cone_degrees", options.patches.cone_angle * 180.0 / M_PI)
        .add ("file_tolerance", model_path.empty () ? 0.0 : write_options.tolerance)
        .add ("file_extent_bits", model_path.empty () || write_options.tolerance == 0.0 ? 0 : write_options.extent_bits)
        .add ("file_refine_steps", model_path.empty () || write_options.tolerance == 0.0 ? 0.0 : write_options.footprint_refine_steps)
        .add ("file_candidates_measured", file_choice.measured)
        .add ("file_candidates_confirmed", file_choice.confirmed)
        .add ("nnz", stats.num_nonzeros)
        .add ("cr", stats.compression_ratio)
        .add ("rmse", stats.rmse)
        .add ("rmse_over_diag", stats.rmse_over_diagonal)
        .add ("mean_error_over_diag", stats.mean_error_over_diagonal)
        .add ("max_error", stats.max_error)
        .add ("bbox_diagonal", model.bbox_diagonal)
        .add ("uncovered", stats.uncovered)
        .add ("faces_in_no_patch", face_coverage.faces_in_no_patch)  // untiled only (0 tiled)
        .add ("area_in_no_patch", face_coverage.area_fraction)
        .add ("flipped_places_cut", tiled ? 0 : encoder.getFlippedPlaceTrim ().places)  // untiled only
        .add ("patches_cut_at_flips", tiled ? 0 : encoder.getFlippedPlaceTrim ().patches)
        .add ("tiles", tiled ? tiled_model.tiles.size () : 0)
        .add ("ranks", group.size ())
        .add ("spilled", bounded)
        .add ("held_tiles", tiled_report.held_tiles)
        .add ("held_vertex_listings", tiled_report.held_listings)
        .add ("pending_tiles", tiled_report.pending_tiles)
        .add ("peak_mb", tools::JsonObject ()
                           .add ("load", peak_after_load)
                           .add ("encode", peak_after_encode)
                           .add ("write", peakResidentMb ()))
        .add ("seconds", tools::JsonObject ()
                           .addSeconds ("load", load_seconds)
                           .addSeconds ("patches", t.patches)
                           .addSeconds ("coding", t.coding)
                           .addSeconds ("encode", t.total)
                           .addSeconds ("statistics", statistics_seconds)
                           .addSeconds ("write", write_seconds));
      if (const ScanCleaningReport* cleaning = tools::cleaningReportOf (input, source.get ()))
        tools::addInputJson (object, cleaning, encoder.getCloudSurface ().get ());
      object.print ();
    }
    else
    {
      std::printf ("%10s %7s %8s %8s %11s %10s %6s\n", "N_V", "M", "rho", "nnz", "RMSE", "RMSE/diag", "CR");
      std::printf ("%10zu %7zu %8g %8zu %11.4e %10.3e %6.3f\n", stats.num_vertices, stats.num_patches,
                   options.patches.rho, stats.num_nonzeros, stats.rmse, stats.rmse_over_diagonal,
                   stats.compression_ratio);
      if (stats.uncovered > 0 && tools::cleaningReportOf (input, source.get ()))  // a scan
        std::printf ("uncovered points (not in the RMSE): %zu, in no triangle beside the surface, whose patches resample "
                     "there (-point-patches 0: a patch each)%s\n",
                     stats.uncovered, tiled ? ", or in tiles too small to make a surface" : "");
      else if (stats.uncovered > 0)
        std::printf ("uncovered vertices (not in the RMSE): %zu\n", stats.uncovered);
      if (tiled)
        std::printf ("tiles: %zu with patches of %zu (%d x %d x %d, edge %.4g), %d process%s\n", tiled_model.tiles.size (),
                     tiled_model.grid.size (), tiled_model.grid.counts.x (), tiled_model.grid.counts.y (),
                     tiled_model.grid.counts.z (), tiled_model.grid.edge, group.size (), group.size () > 1 ? "es" : "");
      if (bounded)
        std::printf ("input spilled into tiles on disk (%zu points in the file, more than -memory holds)\n", header_points);
      tools::printScanSummary (tools::cleaningReportOf (input, source.get ()), encoder.getCloudSurface ().get ());
      if (tiled)  // patches and coding as one (printed as "patches 0.000" before)
        std::printf ("seconds: load %.3f, patches and coding %.3f, statistics %.3f, write %.3f (encode %.3f)\n",
                     load_seconds, t.coding, statistics_seconds, write_seconds, t.total);
      else
        std::printf ("seconds: load %.3f, patches %.3f, coding %.3f, statistics %.3f, write %.3f (encode %.3f)\n",
                     load_seconds, t.patches, t.coding, statistics_seconds, write_seconds, t.total);
    }
    return 0;
  }));
}
