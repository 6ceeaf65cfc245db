#pragma once
/// @file
/// The data of the browser report (docs/report.md): one JSON object that the page embeds and
/// draws. It holds the scene's bodies as drawable parts in their body frames, and for a run
/// its samples (every output column), the events, contact-mode changes and impacts, and the
/// reactions and contact forces at each sample; for a solve the forces of the solved instant.
/// Long arrays are base64 text of little-endian numbers ("f8": 64-bit, exact; "f4": 32-bit,
/// for drawing and plotting only), so a 10,000-sample, 10-body run stays a few megabytes.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "chasles/analysis/solve_report.h"
#include "chasles/analysis/study.h"
#include "chasles/scene/modes.h"
#include "chasles/scene/scene.h"

namespace chasles {

/// The output columns a report plots besides `columns` (a run's own): the ledger, reaction and
/// contact columns. `columns` first, in order (t first); missing ones appended. The poses the
/// replay draws are no columns: the run records them from its states
/// (StudyOptions::record_row_poses).
std::vector<std::string> ReportColumns(const Scene& scene, const std::vector<std::string>& columns);

/// Where the poses of a run's report come from (the data's "poses_from").
enum class PoseSource {
  kStates,   ///< "states": recorded from the run's states (StudyResult::row_poses)
  kColumns,  ///< "columns": reconstructed from a finished run's table (PosesFromColumns)
};

/// The poses read from a finished run's table.
struct ColumnPoses {
  /// Per row of the table, every scene body's pose (the layout of StudyResult::row_poses).
  std::vector<std::vector<StudyBodyPose>> rows;
  /// The bodies whose origin was derived from the centre of mass (no origin columns).
  std::vector<std::string> derived;
};

/// Every body's pose at every row of a finished run's table, for `chasles report` of a run's
/// CSV, which holds columns and no states: the one place the report reads poses by column
/// name. Per body the origin from `<body>_ox, _oy, _oz`, or else Bo = Bcm − R_WB p_BoBcm_B from
/// `<body>_x, _y, _z` (planar: `_z` or 0); the orientation from `<body>_qw..qz` (normalised) or,
/// planar, `<body>_theta` (q = [cos θ/2, 0, 0, sin θ/2]); quaternions with w >= 0. Throws
/// InputError naming the body and the columns it lacks.
ColumnPoses PosesFromColumns(const Scene& scene, const StudyResult& result);

/// The scene part of every report: kind, title, scene file, planar flag, units, and per body
/// its parts as primitives or meshes (in B), centre of mass, inertia about it, principal
/// moments and axes, named points. Mesh files are read again (their vertices, scaled to m).
nlohmann::json ReportSceneJson(const Scene& scene, const std::string& kind);

/// The report of a run: ReportSceneJson plus "samples", "columns" (name, unit, group, type,
/// data: f8 for t, f4 otherwise), "poses_from" (`from`: "states" or "columns") and "poses" (per
/// body, by its index in "bodies": its origin and quaternion [w, x, y, z] at every sample, f8,
/// from the result's row_poses, which must hold every body at every row; InputError
/// otherwise), "events", "contact_events", "impacts", "jumps" and, when the result has row
/// snapshots, "reactions" (per constraint: point and force in W at each row, f4), "contacts"
/// (per point: position, normal force N n and friction force in W at each row, f4, and the
/// mode of each row) and "forces" (docs/report.md, "The data").
nlohmann::json SimulationReportData(const Scene& scene, const StudyResult& result,
                                    PoseSource from = PoseSource::kStates);

/// The mass report: ReportSceneJson(scene, "mass").
nlohmann::json MassReportData(const Scene& scene);

/// The report of one solve: ReportSceneJson plus the instant's body poses (the scene's initial
/// state), reactions and contact points with their forces, in W.
nlohmann::json SolveReportData(const Scene& scene, const SolveReport& report);

/// The report of a sweep (`command`: "simulate", "solve" or "mass"): ReportSceneJson(scene,
/// "sweep") of the scene at its own parameter values, "command", "poses" (the scene's initial
/// configuration, as SolveReportData; none for "mass": the bodies at their frames) and "sweep"
/// (SweepJson of the table: parameters, columns, units, rows with null for a failed point's
/// values, errors).
nlohmann::json SweepReportData(const Scene& scene, const SweepTable& table,
                               const std::string& command);

/// The report of a scene's modes (`chasles modes --html`): ReportSceneJson(scene, "modes") plus
/// the operating point ("kind", "residual"), the bodies there ("poses": origin, quaternion and
/// centre of mass in W), the coordinates and speeds, "amplitude" (the fraction of the scene's
/// size the largest excursion is drawn as, and that size) and per mode its eigenvalue,
/// frequency, damping, stability, shape and, when the page animates it (not a rigid mode), the
/// stretch of time it loops over, the scale ε of the shape and each body's complex
/// displacement and rotation times ε (CalcBodyModeShapes; docs/report.md, "Modes").
nlohmann::json ModesReportData(const Scene& scene, const OperatingPointModes& modes);

/// `bytes` as base64 (RFC 4648, with padding).
std::string Base64(const void* bytes, size_t size);

}  // namespace chasles
