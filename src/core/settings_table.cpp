#include "core/settings_table.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <unordered_map>

#include "core/error.h"
#include "core/format.h"

namespace inim {

namespace {

constexpr double kText = std::numeric_limits<double>::quiet_NaN();
constexpr double kMaxSpp = 1 << 20;       // samples per pixel or per ray
constexpr double kMaxPixels = 32768;      // image width or height
constexpr double kMaxDistanceMm = 10000;  // 10 m: any bench, any room
constexpr double kMaxCount = 1e6;         // patches, views, hold-out colours
constexpr double kMaxReachMm = 1e7;       // positions in a scene: the ray tracer's reach (core/ray_check.h)

// A setting whose value is text, a file or a switch.
SettingInfo text(std::string_view key, std::string_view scope, std::string_view help) {
  return {key, scope, kText, kText, "", help};
}
SettingInfo choice(std::string_view key, std::string_view scope, std::string_view choices, std::string_view help) {
  return {key, scope, kText, kText, choices, help};
}
SettingInfo number(std::string_view key, std::string_view scope, double lo, double hi, std::string_view help) {
  return {key, scope, lo, hi, "", help};
}
// A number in the JSON files (kFileScope).
SettingInfo file(std::string_view key, double lo, double hi, std::string_view help) {
  return {key, kFileScope, lo, hi, "", help};
}

// Every run, its inputs and their placement.
std::vector<SettingInfo> runAndInputSettings() {
  return {
      // Every run
      text("seed", "", "Random seed, a whole number 0 to 2^64-1; output depends on it only (default: 1)"),
      number("threads", "", 0, 4096, "Worker threads (0 = all cores)"),
      text("quiet", "", "Print nothing but warnings"),
      text("quiet", "eval", "Print only the means"),
      text("run", "", "Run file (JSON): placement and settings; command-line options override it"),
      text("run", "rays", "With --for-field: run file of the EIA (placement, VCP, spp)"),
      text("run", "view", "--reference: the EIA's run file (scene, placement)"),
      text("run", "reference", "Run file of the EIA (placement, scene, display); options override it"),
      text("run", "place", "Run file to start from (placement, display, VCP, layout)"),
      // Inputs: display, scene or field, camera
      text("display", "", "Display JSON (default: optics/displays/paper-prototype.json)"),
      text("display", "reference",
           "Display JSON (default: the run file's, else the paper prototype): checks that the display area is in view"),
      text("display", "capture", "Display whose area frames the default target (default: the paper's)"),
      choice("layout", "", "parallel,toed-in,lens-grid", "EI layout (default: the display's)"),
      number("viewing_distance_mm", "", 1, kMaxDistanceMm, "Viewing distance D for toed-in, mm (default: the display's)"),
      text("scene", "", "Scene JSON (default: scenes/paper-fig7.json)"),
      text("field", "",
           "The field: a scene JSON, a trained radiance field (.inimrf) or Gaussian splats (.ply, .splat) (default: "
           "scenes/paper-fig7.json)"),
      text("field", "render",
           "Scene JSON, a trained radiance field (.inimrf) for novel views in its own units and frame, or Gaussian "
           "splats (.ply, .splat; placed in the display frame) (default: scenes/paper-fig7.json)"),
      text("field", "view", "--reference: the EIA's scene or field (default: the run file's, else scenes/paper-fig7.json)"),
      text("field", "reference",
           "Scene JSON, trained radiance field (.inimrf) or Gaussian splats (.ply, .splat) (default: the run file's, "
           "else scenes/paper-fig7.json)"),
      text("camera", "", "Camera: a name in optics/cameras/ or a JSON file"),
      // Placement
      text("scale", "",
           "Placement scale, display mm per field unit: S or sx,sy,sz (analytic scenes are in mm: 1; the paper's NeRF "
           "at 0.0075 units/mm: 133.33)"),
      text("rotate_deg", "", "Placement rotation rx,ry,rz (x, then y, then z), degrees"),
      text("translate_mm", "", "Placement translation x,y,z in mm (applied last)"),
  };
}

// eia and rays: synthesis, outputs, ray files.
std::vector<SettingInfo> synthesisSettings() {
  return {
      // Synthesis (eia, rays --for-field)
      number("vcp_mm", "", -kMaxDistanceMm, kMaxDistanceMm, "VCP distance D_VCP in front of the MLA (the near clipping plane), mm"),
      number("vcp_mm", "rays", -kMaxDistanceMm, kMaxDistanceMm, "With --for-field: VCP distance in front of the MLA, mm"),
      number("spp", "", 1, kMaxSpp, "Samples per pixel"),
      number("spp", "eia", 1, kMaxSpp, "Field samples per display ray (wavelengths, light samples)"),
      number("spp", "rays", 1, kMaxSpp, "With --for-field: samples per display ray, as for inim eia"),
      number("spp", "view", 1, kMaxSpp,
             "Samples per pixel (default: 1 stratum for the quadrature estimator, 16 samples for the sampled ones)"),
      number("spp", "fig11", 1, kMaxSpp,
             "Strata per pixel of the reconstructed views (quadrature estimator: deterministic; with the default "
             "aperture grid RMSE 2.5% of the mean against 16 strata on a 32 x 32 grid at 648 px, 2.2% at 2 strata in "
             "1.5 x the time)"),
      text("exposure", "eia",
           "Drive = E x panel-native RGB (field luminance 1/E = panel white), or auto (default: the 99th percentile of "
           "the brightest channel of the pixels that see the scene -> full drive)"),
      text("exposure", "",
           "Exposure factor applied to the EXR and the PNG, or auto (99th percentile of the brightest channel -> 0.9)"),
      choice("gamut", "", "clip,desaturate", "Out-of-gamut mapping: clip (per channel) or desaturate"),
      choice("white_balance", "", "none,d65", "White gains: none (colorimetric) or d65 (gains so that D65 drives 1,1,1)"),
      text("calibration", "",
           "Panel calibration applied to the drive values after the gamut mapping: a 3D LUT (.cube or .clf, drive -> "
           "drive, e.g. from `inim calibrate`; default: none)"),
      text("triad_wavelengths", "",
           "Triad wavelengths: panel (primary peaks, default), paper (656,566,471), zemax-sequential (620,525,460) or "
           "R,G,B in nm"),
      text("field_colors", "",
           "Colours of an external field, one per query ray written by `inim rays --for-field` with the same display, "
           "placement and settings (.npy or .exr: R G B [A [depth]])"),
      choice("field_colors_encoding", "", "srgb,linear", "How --field-colors values are encoded (NeRF outputs: srgb)"),
      text("aovs", "", "Add A (opacity) and Z (display z of the first surface, mm) channels to the EXR"),
      text("preview", "", "Placement preview PNG (central ray of each lenslet, like the paper's Fig. 4)"),
      text("real_lens", "eia",
           "Query the scene along the real-lens display rays (traced through the refracting MLA at the physical lens "
           "centres) instead of the pinhole rays"),
      text("real_lens", "rays",
           "Trace every pixel's ray through the real MLA (refraction at n(lambda), the physical lens centres) instead "
           "of the pinhole model; origins moved back to z = 0"),
      choice("chief_rays", "", "pinhole,traced",
             "Display rays: pinhole (the pinhole model's; the default for one thin lens array) or traced (each "
             "pixel's real chief ray through the display's optical stack, its aperture stop's centre; the default "
             "for other stacks)"),
      choice("real_lens_ray", "", "centroid,chief",
             "With --real-lens: centroid (the power centroid of each pixel's exit bundle through its lenslet) or chief "
             "(the ray through the lenslet's aperture centre)"),
      number("wavelength_nm", "", 360, 830, "With --real-lens or --chief-rays traced: the wavelength, nm"),
      number("wavelength_nm", "lens info", 360, 830, "Wavelength of the trace, nm"),
      // Outputs
      text("out", "", "Output folder"),
      text("out", "eia", "Output EXR of linear drive values at the panel resolution"),
      text("out", "rays", "Output: FILE.txt (Zemax ray text, \"x, y, z, l, m, n\" %.8f) or FILE.irays"),
      text("out", "view", "Output EXR: linear, white-balanced camera RGB x exposure"),
      text("out", "reference", "Output EXR: linear, white-balanced camera RGB x exposure"),
      text("out", "render", "Output EXR (linear Rec.709 + A + Z); an sRGB PNG is written beside it"),
      text("out", "query", "Colour table (.npy: float32 N x 5, or .exr: R G B A Z)"),
      text("out", "triads export", "Output .sdf"),
      text("out", "triads form", "Output EXR (panel resolution, channels R, G, B: summed flux)"),
      text("out", "train", "Model file (.inimrf)"),
      text("out", "eval", "Folder for the rendered views (PNG, beside the photos) and metrics.json/.csv"),
      text("out", "place", "The only folder the page writes into"),
      text("png", "", "Encoded PNG (default: beside --out, same name, .png)"),
      text("png", "triads form", "Also an encoded PNG (the panel's EOTF)"),
      text("sdf", "", "Also write the triads (3 rays per display ray) as a Zemax SDF source file"),
      text("zemax_model", "",
           "With --sdf: also write the paper's non-sequential OpticStudio model (.zmx): the SDF as a source file "
           "object and a colour detector sized and pixelled as the EIA at the display's gap"),
      text("sdf", "triads form", "Zemax spectral source file (.sdf)"),
      // rays
      number("gap_mm", "rays", 1e-3, 1000, "Generate at this panel gap instead of generation_gap_mm"),
      number("gap_mm", "view", 1e-3, 1000, "Panel to MLA reference plane, mm (default: the display's reconstruction gap)"),
      number("gap_mm", "triads form", 1e-3, 1000, "Detector at z = -G (default: the display's generation gap)"),
      text("zemax_macro", "", "Text as the paper's ZPL macro wrote it: UTF-16LE with BOM, CRLF, two header lines"),
      text("ei", "",
           "Only EI K,L (K from the left, L from the top), positions relative to its pinhole (the macro's single-EI "
           "file); .txt only"),
      text("in", "",
           "Convert this ray file (.txt: Zemax text, UTF-8 or UTF-16LE; .irays) to --out instead of generating rays"),
      text("for_field", "",
           "Write the orthoscopic QUERY rays instead (field frame, after the inverse placement; reversed display rays "
           "starting on the VCP) as a table for an external radiance field: --out FILE.npy (float32 N x 8: ox oy oz "
           "dx dy dz near far) or FILE.exr; fill in one colour per row and pass it to `inim eia --field-colors`"),
  };
}

// view, reference, fig11 and calibrate.
std::vector<SettingInfo> viewSettings() {
  return {
      // view and reference: camera and pose
      text("camera_model", "", "Camera model (default: the camera file's)"),
      number("distance_mm", "", 1, kMaxDistanceMm,
             "Camera (entrance pupil) to display centre, mm (default: the camera file's distance_mm)"),
      number("rot_h_deg", "", -360, 360,
             "Display rotation about its vertical axis, degrees; + turns its right edge away from the camera"),
      number("rot_v_deg", "", -360, 360,
             "Display rotation about its horizontal axis, degrees; + turns its top edge away from the camera"),
      number("focus_mm", "", 1e-3, kMaxDistanceMm,
             "Focus distance from the entrance pupil, mm (default: the camera distance, i.e. the MLA plane)"),
      number("width", "", 1, kMaxPixels, "Image width, pixels"),
      number("width", "view", 1, kMaxPixels,
             "Image width in pixels (default: the sensor's; a smaller width keeps the field of view and scales the "
             "pixel pitch)"),
      number("width", "reference", 1, kMaxPixels,
             "Image width in pixels (default: the sensor's; a smaller width keeps the field of view and scales the "
             "pixel pitch)"),
      number("width", "fig11", 1, kMaxPixels, "View width in pixels (the sensor's pixel pitch scales; 2592 = full)"),
      number("width", "calibrate", 1, kMaxPixels, "View width in pixels of the measuring renders"),
      number("height", "", 1, kMaxPixels, "Image height, pixels"),
      number("height", "view", 1, kMaxPixels, "Image height in pixels (default: the sensor's aspect ratio)"),
      number("height", "reference", 1, kMaxPixels, "Image height in pixels (default: the sensor's aspect ratio)"),
      text("camera_dispersion", "",
             "auto (trace the camera lens per wavelength only when it spreads a point's colours over more than 0.25 "
             "px), trace, or ignore (rays at 550 nm carry every wavelength)"),
      // view: the display model and estimator
      text("eia", "",
           "EIA: linear drive values (EXR from inim eia), panel-sized or EIA-sized; a PNG is decoded through the "
           "panel's EOTF"),
      text("eia", "triads export", "EIA EXR (panel or EIA size; the first three channels are R, G, B)"),
      text("mla", "view", "MLA model: real (refracting lenslets) or ideal (paraxial thin lenses, the pinhole-MLA comparison)"),
      choice("mla", "", "real,ideal", "MLA model for the reconstruction: real (refracting) or ideal (thin lenslets)"),
      text("spectral", "",
           "Wavelength sampling: primaries (importance-sampled per panel primary) or visible (4-wavelength packets)"),
      choice("estimator", "", "point,footprint,quadrature,auto",
             "Panel estimator: point (subpixel under each ray), footprint (box average over the sample's share of the "
             "pixel footprint), quadrature (pixel area, aperture and spectra all by quadrature, no noise; spp = strata "
             "per pixel, default 1) or auto (quadrature: the lowest error for the time at every width in inim bench)"),
      number("aperture_grid", "", 2, 64,
             "quadrature: the camera aperture's quadrature table, N x N cells over the exit pupil"),
      number("aperture_grid", "fig11", 2, 64,
             "Aperture quadrature grid of the reconstructed views (N x N cells over the exit pupil; 16: RMSE 1.1% at 4 "
             "strata, 2.2 x the time)"),
      number("wavelength_nodes", "", 1, 64,
             "quadrature, when something is dispersive: wavelength nodes per primary (1: each primary's median "
             "wavelength, weighted by its whole spectrum)"),
      number("background", "", 0, 1e6,
             "Luminance of the (D65 grey) background around the display, in the image's units (default 0: black)"),
      number("emission_cos_n", "", 0, 1000, "Extra cos^n angular emission profile on top of the panel's (0: none)"),
      text("no_cover_glass", "", "Ignore the panel's cover glass"),
      text("no_cull", "", "Trace every tile, also those that cannot see the display"),
      text("relative", "", "Panel white = luminance 1 instead of its peak luminance in cd/m^2"),
      // view --reference and fig11: the reference and the error budget
      text("reference", "",
           "Also render the scene itself from the same pose and compare (as inim fig11 does): NAME_reference, "
           "NAME_error.png, NAME_metrics.json and the error budget NAME_budget.json|csv|png beside --out"),
      number("eia_exposure", "", 0, 1e12,
             "--reference: the EIA's drive per unit field luminance (default: its EXR header, written by inim eia and "
             "inim fig11)"),
      number("reference_spp", "", 1, kMaxSpp, "Samples per pixel of the reference"),
      number("eia_spp", "", 1, kMaxSpp, "Field samples per display ray for the EIA"),
      text("no_budget", "", "--reference: compare only, without the error budget"),
      text("budget", "",
           "Error budget per view: the ladder from an ideal display to the real one, the full chain with one effect "
           "removed, the noise floor (budget.json, budget.csv, budget.png)"),
      text("budget_rungs", "",
           "Only these budget rungs (comma separated): ideal, +subpixels, +real_mla, +cover_glass, +colour_chain, "
           "+calibration, -subpixels, -real_mla, -cover_glass, -colour_chain; a stack display's +apertures, +barriers, "
           "-apertures, -barriers"),
      text("budget_calibration", "",
           "The budget's calibration rung: a .cube or .clf from inim calibrate (default: --calibration)"),
      number("budget_spp", "", 1, kMaxSpp,
             "Strata per pixel of every rung, the full chain included (1: RMSE 2.5% of the mean, within 3x the plain "
             "run's time; --spp's value reuses the run's own view as the full chain)"),
      // fig11 and calibrate: poses
      number("angle", "", -360, 360, "Viewing angle of the side views, degrees"),
      text("poses", "", "Only these poses (comma separated): centre, left, right, top, bottom (the first is the headline)"),
      // calibrate
      text("assumed_display", "",
           "The display the EIAs are made for, when the panel shown differs from its description (e.g. placeholder "
           "primaries in the file, measured ones in the panel) (default: --display)"),
      text("grade", "calibrate",
           "MEAN,MAX: the CIEDE2000 each pose's in-gamut hold-out must meet through the exported correction "
           "(DisplayCAL's recommended 1,3); a pose that misses it makes the exit status 3; off: no grade"),
      choice("field_space", "", "lin_rec709,display_p3,acescg,spectral", "The field's colour space"),
      number("grid_levels", "", 2, 64, "Levels per channel of the drive grid used to fit"),
      number("holdout", "", 0, kMaxCount, "Hold-out colours from the panel's gamut"),
      number("holdout_out_of_gamut", "", 0, kMaxCount, "Hold-out colours outside it (inside Rec.2020)"),
      text("patches", "", "More colours to verify: a CSV with columns name,X,Y,Z (D65 white Y = 1)"),
      choice("correction", "", "auto,matrix_3x3,root_polynomial_2,lut3d",
             "Exported model: auto (lowest hold-out error at the first pose), matrix_3x3, root_polynomial_2 or lut3d"),
      number("lut_size", "", 2, 256, "Nodes per axis of the exported 3D LUT"),
      number("panel_bits", "", 0, 32, "Bits of the panel's encoded input (0: float)"),
      number("direct_checks", "", 0, kMaxCount, "Patches rendered directly to check the linear chain model"),
  };
}

// render, capture, train, eval, query, triads, compare, lens, place, study, bench.
std::vector<SettingInfo> otherCommandSettings() {
  return {
      // render
      text("eye", "", "Camera position x,y,z in mm (display frame)"),
      text("look_at", "", "Point the camera looks at, mm"),
      text("up", "", "Up vector"),
      number("fov", "", 1e-3, 179.9, "Horizontal field of view, degrees"),
      number("aperture", "", 0, 1000, "Thin-lens aperture diameter, mm (0 = pinhole)"),
      number("focus", "", 1e-3, kMaxDistanceMm, "Focus distance, mm (default: eye to look-at)"),
      choice("integrator", "", "direct,path", "direct (default in scenes) or path (NEE + MIS)"),
      number("max_depth", "", 0, 1000, "Maximum scattering depth (overrides the scene)"),
      // capture
      number("views", "", 1, kMaxCount, "Number of views"),
      number("hfov_deg", "", 1e-3, 179.9, "Horizontal field of view, degrees"),
      text("elevation_deg", "", "Elevation range above the display plane, min,max degrees"),
      text("target", "",
           "What the views frame: x0,y0,z0,x1,y1,z1 in mm (default: the scene's bounds within the display's lenslet "
           "area in x, y and within +-VCP in z, i.e. what the display can show)"),
      number("radius_mm", "", 0, kMaxDistanceMm, "Camera distance from the target centre (default: framing the target)"),
      // train and eval
      text("data", "",
           "Dataset: a folder with transforms.json / transforms_train.json (Blender, Nerfstudio, instant-ngp) or a "
           "Middlebury *_par.txt, or the file itself"),
      number("downscale", "", 1, 64, "Integer image downscale factor (intrinsics follow)"),
      number("holdout_every", "", 0, kMaxCount, "Frame i is held out for testing when i % N == 0 (0: none)"),
      text("background", "train", "What transparent pixels composite onto: white, black or r,g,b"),
      text("background", "eval", "What transparent pixels composite onto: white, black or r,g,b"),
      text("log", "", "CSV log of iteration, loss, PSNR, time (default: beside --out, .csv)"),
      number("iterations", "", 1, 1e8, "Training iterations"),
      number("batch", "", 1, 1 << 24, "Rays per iteration"),
      number("time_budget_s", "", 0, 1e7, "Also stop after this many seconds (then not deterministic)"),
      number("sh_degree", "", 0, 2, "Spherical-harmonic degree of the colour"),
      text("resolutions", "", "Grid resolution (longest side, vertices) of each stage"),
      text("stage_starts", "", "Iteration at which each stage starts (default: 0, then 1/6 and 1/2 of the iterations)"),
      text("model", "", "Model file (.inimrf)"),
      text("all", "", "Evaluate every frame, not only the held-out ones"),
      // query
      text("field", "query", "Scene JSON, trained radiance field (.inimrf) or Gaussian splats (.ply, .splat)"),
      text("rays", "", "Ray table (.npy or .exr) from `inim rays --for-field`"),
      // triads
      number("flux_scale", "", 0, 1e12, "Flux = drive value x this (default 1)"),
      text("skip_zero", "", "Leave out triad rays of flux 0 (the paper wrote them all)"),
      text("flux_sum", "", "Header ray-set flux = sum of the ray fluxes (the paper wrote 1)"),
      // compare
      text("json", "", "Print JSON instead of text"),
      text("json", "compare",
           "Print JSON: psnr_db (null if identical), ssim, de2000_mean, de2000_p95, de2000_max, pixels, ..."),
      text("json", "lens info", "Print JSON (keys efl_mm, bfl_mm, ffl_mm, f_number, entrance_pupil, ...)"),
      text("mask", "",
           "Mask image of the same size: a single-channel image or the alpha of an image; pixels with value > 0.5 "
           "count, the others have no influence on any metric"),
      text("space", "",
           "Colour space of both images (lin_rec709, srgb, display_p3, acescg, cie_xyz_d65); default: lin_rec709 for "
           "EXR/HDR files, srgb for PNG/JPEG/TIFF, per file"),
      text("values", "", "PSNR and SSIM on sRGB-encoded values or on linear Rec.709 values"),
      text("ssim", "", "SSIM on luminance, or the mean of per-channel SSIMs"),
      number("peak", "", 1e-12, 1e12, "PSNR peak value and SSIM dynamic range L, in the units of --values"),
      number("white_luminance", "", 1e-12, 1e12,
             "Y of the reference white for CIELAB, in the images' linear units (1: RGB (1,1,1) is L* = 100)"),
      text("de_map", "", "Also write the per-pixel CIEDE2000 as a single-channel EXR"),
      // lens
      choice("thickness_convention", "", "after,before",
             "Override the file's thickness convention: 'after' (distance to the next surface, pbrt/Zemax) or "
             "'before' (distance from the previous surface)"),
      // place
      number("port", "", 0, 65535, "Port to listen on (0: a free one)"),
      text("host", "", "Address to listen on (an IPv4 address or localhost); anything but loopback exposes the page"),
      // study
      text("quick", "", "The CI-sized form the tests run (fewer depths, smaller images and budgets; its own tolerances)"),
      // bench
      text("filter", "", "Regex of benchmarks to run"),
      number("min_time", "", 0, 1e4, "Minimum seconds per benchmark"),
      number("view_width", "", 1, kMaxPixels, "Image width of the view/ benchmarks (2592 = the sensor)"),
      number("view_spp", "", 1, kMaxSpp, "Samples per pixel of the view/ benchmarks (comma separated)"),
      choice("view_estimators", "", "point,footprint,quadrature", "Panel estimators of the view/ benchmarks"),
      number("view_ref_spp", "", 0, kMaxSpp, "spp of view/reference; 0: 16x the largest --view-spp"),
      number("view_grid", "", 2, 64, "Aperture table grid of the quadrature view/ runs"),
      number("view_ref_grid", "", 0, 64,
             "Aperture table grid of their references (0: --view-grid; larger: the table's own error shows in the "
             "RMSE)"),
      text("field_model", "", "Trained model (.inimrf) for radiance/eia-query and the place/ model runs"),
      text("field_scale", "", "Its placement scale, mm per field unit (default: the model's)"),
      text("field_rotate_deg", "", "Its placement rotation rx,ry,rz, degrees"),
      text("field_translate_mm", "", "Its placement translation, mm"),
      text("lego", "", "Lego dataset folder for radiance/train-lego (e.g. ../shared/data/lego)"),
      number("lego_iterations", "", 1, 1e8, "Training iterations of radiance/train-lego"),
      // sweep
      text("plan", "", "The sweep's plan (JSON: a base design and the axes to vary; docs/sweeps.md)"),
      text("out", "sweep", "The sweep's folder: plan.json, points/ID/, references/, results.csv/.json, plots/, report.md"),
      number("jobs", "", 1, 4096, "Points run at once, each its own process"),
      number("threads_per_point", "", 0, 4096, "Worker threads of each point (0: the machine's threads / --jobs)"),
      number("max_points", "", 1, 1e9, "Refuse a plan that makes more points than this"),
      text("slurm", "", "Write a Slurm job array for the points not complete, and its collection step (DIR/slurm/)"),
      text("submit", "", "With --slurm: submit both with sbatch and print the job ids"),
      text("partition", "", "With --slurm: the partition (default: the cluster's)"),
      number("cpus_per_task", "", 1, 4096, "With --slurm: CPUs of each array task (its points' threads)"),
      text("mem", "", "With --slurm: memory of each array task, as sbatch --mem takes it"),
      text("time_limit", "", "With --slurm: time limit of each array task, as sbatch --time takes it"),
      number("points_per_task", "", 1, 1e6, "With --slurm: points run one after another by each array task"),
      text("point", "", "Run this point of the sweep in --out alone (its id, as point.json and the report give it)"),
      text("collect", "", "Gather the points' results of the sweep in --out: results.csv/.json, plots, report.md"),
      text("slurm_task", "", "A Slurm array task's list of points (DIR/slurm/tasks-N.txt; the array script gives it)"),
      text("reference_cache", "",
           "The points' reference cache: a folder (on a cluster, on the shared file system), or off (default: "
           "DIR/references)"),
      number("task_index", "", 0, 1e9, "With --slurm-task: the array task's index ($SLURM_ARRAY_TASK_ID)"),
  };
}

// Numbers in the JSON files.
std::vector<SettingInfo> fileSettings() {
  return {
      // Keys of the JSON files (scope "file": every file format that has the key; the general
      // entry of the same key, above, holds where there is no file entry).
      // Placement (run files, scene objects, the placement page)
      file("scale", 1e-12, 1e15, "A scale factor > 0: placement (display mm per field unit), a spectrum's or a light's, a lens file's, a dataset's"),
      file("field_units_per_mm", 1e-9, 1e9, "Placement as the field's units per display mm (the inverse of scale)"),
      file("rotate_deg", -360, 360, "Rotation about x, y, z, degrees (each element)"),
      file("translate_mm", -kMaxReachMm, kMaxReachMm, "Translation x, y, z, mm (each element)"),
      file("triad_wavelengths", 360, 830, "Triad wavelengths R, G, B in nm (each element)"),
      file("angle_deg", -360, 360, "An angle in degrees: a chart's tilt, a placement-page job's viewing angle"),
      // Displays: panel
      file("resolution_px", 1, kMaxPixels, "Panel resolution, pixels (each element)"),
      file("pixel_pitch_mm", 1e-4, 10, "Pixel pitch, mm (0.1 um to 10 mm): a panel's or a camera sensor's"),
      file("peak_luminance_cd_m2", 1e-3, 1e6, "Panel white luminance, cd/m^2"),
      file("gamma", 0.1, 10, "Panel EOTF exponent"),
      file("fill_factor", 1e-3, 1, "Emitting share of a subpixel's cell"),
      file("tile_px", 1, 4096, "Subpixel tile size, pixels (each element)"),
      file("mean_nm", 200, 2000, "Centre wavelength of a Gaussian spectrum, nm"),
      file("fwhm_nm", 0.1, 2000, "Full width at half maximum of a Gaussian spectrum, nm"),
      file("thickness_mm", -kMaxDistanceMm, kMaxDistanceMm, "A thickness, mm: a cover glass's, or a lens surface's distance to the next (signed)"),
      // Displays: MLA and gaps
      file("pitch_mm", 1e-3, 10, "Lenslet pitch, mm (1 um to 10 mm)"),
      file("radius_of_curvature_mm", 1e-3, kMaxDistanceMm, "Lenslet radius of curvature, mm"),
      file("focal_length_mm", 1e-3, kMaxDistanceMm, "Lenslet focal length, mm (within 2% of the one its radius and glass give)"),
      file("conic", -1e3, 1e3, "Conic constant of a surface"),
      file("aperture_mm", 0, 1e3, "Clear aperture diameter, mm: a lenslet's or a lens surface's"),
      file("substrate_thickness_mm", 1e-6, 1e3, "MLA substrate thickness, mm"),
      // Displays: optical stacks (optics/README.md)
      file("asphere", -1e6, 1e6, "Even-asphere coefficients of r^4, r^6, ... of a stack surface (each element)"),
      file("lattice_offset_mm", -10, 10, "A stack layer's lattice offset against the panel centre, mm (each element)"),
      file("count", 1, 1 << 20, "Lenslets (holes, cells) of a stack layer's lattice: [columns, rows] (each element)"),
      file("hole_mm", 1e-4, 10, "Hole size of an aperture-array layer, mm"),
      file("wall_mm", 0, 10, "Wall width of a barrier layer, mm"),
      file("wall_reflectance", 0, 1, "Reflectance of a barrier layer's walls (0: absorbing)"),
      file("panel_radius_mm", -kMaxDistanceMm, kMaxDistanceMm, "Radius of a curved panel, mm"),
      file("generation_gap_mm", 1e-3, 1e3, "Panel to pinhole plane gap of the generation model, mm"),
      file("reconstruction_gap_mm", 1e-3, 1e3, "Panel to MLA reference plane gap of the reconstruction, mm"),
      // Glasses
      file("nd", 1, 4, "Refractive index at the d line"),
      file("vd", 1, 200, "Abbe number"),
      file("Vd", 1, 200, "Abbe number (material catalogue)"),
      file("n", 1, 5, "A constant refractive index"),
      file("sellmeier_b", -1e6, 1e6, "Sellmeier B coefficients (each element)"),
      file("sellmeier_c", -1e6, 1e6, "Sellmeier C coefficients, um^2 (each element)"),
      file("ior", 1e-3, 10, "Index of refraction of a dielectric material"),
      file("A", 1, 5, "Cauchy A (the index far into the red), material catalogue"),
      file("B", -1e6, 1e6, "Cauchy B, um^2; or Sellmeier B coefficients (each element), material catalogue"),
      file("C", -1e6, 1e6, "Cauchy C, um^4; or Sellmeier C coefficients, um^2 (each element), material catalogue"),
      // Cameras and lens files
      file("width_px", 1, 65536, "Sensor width, pixels"),
      file("height_px", 1, 65536, "Sensor height, pixels"),
      file("f_number", 0.5, 1000, "Lens f-number"),
      file("focus_distance_mm", 1e-3, 1e7, "Focus distance, mm"),
      file("radius_mm", -1e7, 1e7, "A radius, mm: a scene sphere's or cylinder's (> 0), a lens surface's curvature (signed, 0 = flat)"),
      // Scenes
      file("spp", 1, kMaxSpp, "Samples per pixel"),
      file("max_depth", 0, 1000, "Maximum scattering depth"),
      file("rr_depth", 0, 1000, "Depth at which Russian roulette starts"),
      file("id", 0, 2147483647, "Object id (unique in the scene)"),
      file("height_mm", 1e-6, kMaxReachMm, "A height, mm: a cylinder's, a stack's barrier walls'"),
      file("position_mm", -kMaxReachMm, kMaxReachMm, "A light's or camera's position, mm (each element)"),
      file("look_at_mm", -kMaxReachMm, kMaxReachMm, "The point a light or camera looks at, mm (each element)"),
      file("direction", -1e6, 1e6, "A direction (each element; normalised when read)"),
      file("center_mm", -kMaxReachMm, kMaxReachMm, "A centre, mm (each element)"),
      file("size_mm", 0, kMaxReachMm, "A size, mm (each element)"),
      file("period_mm", 1e-3, kMaxReachMm, "A chart's period, mm"),
      file("tick_mm", 1e-3, kMaxReachMm, "A chart's tick length, mm"),
      file("line_mm", 1e-3, kMaxReachMm, "A chart's line width, mm"),
      file("spokes", 1, 1e4, "Spokes of a Siemens star"),
      file("cone_deg", 0, 180, "A spot light's cone angle, degrees"),
      file("falloff_start_deg", 0, 180, "Where a spot light's falloff starts, degrees"),
      file("roughness", 0, 1, "Surface roughness"),
      file("transmittance_thickness_mm", 1e-6, 1e6, "Thickness at which a medium's transmittance is given, mm"),
      file("temperature_k", 100, 1e5, "Blackbody temperature, K"),
      file("cut_nm", 200, 2000, "Edge wavelength of a step spectrum, nm"),
      file("width_nm", 0.1, 2000, "Edge width of a step spectrum, nm"),
      file("lambda_nm", 200, 2000, "Wavelengths of a sampled spectrum, nm (each element)"),
      file("values", 0, 1e12, "Values of a sampled spectrum (each element)"),
      file("value", 0, 1e12, "A constant spectrum's value"),
      file("peak", 0, 1e12, "A Gaussian spectrum's peak value"),
      file("base", 0, 1e12, "A Gaussian spectrum's base value"),
      file("min", 0, 1e12, "A step spectrum's value below the edge"),
      file("max", 0, 1e12, "A step spectrum's value above the edge"),
      // Datasets (transforms.json)
      file("aabb_scale", 1e-6, 1e6, "instant-ngp scene box scale"),
      file("offset", -1e6, 1e6, "instant-ngp scene offset (each element)"),
      file("fl_x", 1e-3, 1e7, "Focal length, pixels"),
      file("fl_y", 1e-3, 1e7, "Focal length, pixels"),
      file("camera_angle_x", 1e-6, 3.14159265358979, "Horizontal field of view, radians"),
      file("camera_angle_y", 1e-6, 3.14159265358979, "Vertical field of view, radians"),
      file("cx", -1e6, 1e6, "Principal point x, pixels"),
      file("cy", -1e6, 1e6, "Principal point y, pixels"),
      file("k1", -1e3, 1e3, "Radial distortion coefficient"),
      file("k2", -1e3, 1e3, "Radial distortion coefficient"),
      file("p1", -1e3, 1e3, "Tangential distortion coefficient"),
      file("p2", -1e3, 1e3, "Tangential distortion coefficient"),
  };
}

std::vector<SettingInfo> makeTable() {
  std::vector<SettingInfo> table;
  for (auto group : {runAndInputSettings, synthesisSettings, viewSettings, otherCommandSettings, fileSettings}) {
    const std::vector<SettingInfo> entries = group();
    table.insert(table.end(), entries.begin(), entries.end());
  }
  return table;
}

bool isNumber(const SettingInfo& info) { return !std::isnan(info.lo); }

}  // namespace

const std::vector<SettingInfo>& settingsTable() {
  static const std::vector<SettingInfo> table = makeTable();
  return table;
}

const SettingInfo* findSetting(std::string_view key, std::string_view scope) {
  // Every number a file gives is looked up: an index by key, not a scan of the table.
  static const std::unordered_multimap<std::string_view, const SettingInfo*> byKey = [] {
    std::unordered_multimap<std::string_view, const SettingInfo*> m;
    for (const SettingInfo& s : settingsTable()) m.emplace(s.key, &s);
    return m;
  }();
  const SettingInfo* general = nullptr;
  for (auto [it, end] = byKey.equal_range(key); it != end; ++it) {
    if (!scope.empty() && it->second->scope == scope) return it->second;
    if (it->second->scope.empty()) general = it->second;
  }
  return general;
}

std::string settingFlag(std::string_view key) {
  std::string flag = "--" + std::string(key);
  for (char& c : flag)
    if (c == '_') c = '-';
  return flag;
}

std::string rangeText(const SettingInfo& info) {
  if (!isNumber(info)) return "";
  return "a number in [" + formatNumber(info.lo, "%.12g") + ", " + formatNumber(info.hi, "%.12g") + "]";
}

void checkSettingRange(const SettingInfo& info, double value, const std::string& file, const std::string& name) {
  if (!isNumber(info) || (value >= info.lo && value <= info.hi)) return;
  throw InputError(file, name, formatNumber(value), rangeText(info));
}

void checkSettingText(const SettingInfo& info, const std::string& text, const std::string& name) {
  if (isNumber(info)) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str()) checkSettingRange(info, v, "", name);
    return;
  }
  if (info.choices.empty()) return;
  for (size_t a = 0, b; a <= info.choices.size(); a = b + 1) {
    b = std::min(info.choices.find(',', a), info.choices.size());
    if (info.choices.substr(a, b - a) == text) return;
  }
  throw InputError("", name, "\"" + text.substr(0, 60) + "\"", "one of: " + std::string(info.choices));
}

std::string allowedText(const SettingInfo& info) {
  if (isNumber(info)) return rangeText(info);
  if (info.choices.empty()) return "";
  std::string text = "{";  // appended, not "{" + string: GCC 12 warns falsely (-Wrestrict) on that
  return text.append(info.choices).append("}");
}

std::string settingsMarkdown() {
  std::string md =
      "# Settings\n\n"
      "Every setting a command or a run file takes: its flag, where it applies, its range or choices, and\n"
      "what it means (flags of the commands, then keys of the JSON files), generated from the table in `src/core/settings_table.cpp` (the test\n"
      "`SettingsTable.DocsListTheTable` fails when they differ and writes the new text). A value\n"
      "outside its range is refused with exit status 2. Defaults are in `--help` and the settings structs.\n\n"
      "| setting | where | range or choices | meaning |\n|---|---|---|---|\n";
  for (const SettingInfo& s : settingsTable()) {
    std::string allowed = isNumber(s) ? rangeText(s).substr(12) : std::string(s.choices);
    for (size_t i = allowed.find(','); !s.choices.empty() && i != std::string::npos; i = allowed.find(',', i + 2))
      allowed.replace(i, 1, ", ");
    std::string help(s.help);
    for (size_t i = help.find('|'); i != std::string::npos; i = help.find('|', i + 2)) help.replace(i, 1, "\\|");
    const bool inFiles = s.scope == kFileScope;
    const std::string where = inFiles ? "JSON files" : s.scope.empty() ? "every command" : std::string(s.scope);
    md += "| `" + (inFiles ? std::string(s.key) : settingFlag(s.key)) + "` | " + where + " | " + allowed + " | " + help +
          " |\n";
  }
  return md;
}

}  // namespace inim
