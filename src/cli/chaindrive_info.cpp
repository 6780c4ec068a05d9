// chaindrive-info: assembles a drive and prints the assembly report; optionally writes the
// geometry (sprocket outlines, guide faces, chain path, pins) as JSON for plots.
#include <cstdio>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/arguments.h"
#include "description/drive_description.h"
#include "assembly/model.h"
#include "description/fields.h"
#include "interface/fmu_files.h"
#include "run/defaults.h"
#include "run/drive_defaults.h"
#include "run/simulation.h"
#include "run/span_damping.h"
#include "span/calibration_cache.h"

using namespace chaindrive;

namespace {

constexpr const char* kTool = "chaindrive-info";

void usage() {
  std::puts(
      "usage: chaindrive-info [--drive FILE] [--geometry OUT.json] [--calibrate] [--span-calibration OUT.json]\n"
      "                       [--quiet]\n"
      "       chaindrive-info --defaults [--drive FILE]\n"
      "       chaindrive-info [--drive FILE] --interface | --fmu-files DIR\n"
      "  Assembles the drive (default: the embedded default drive), prints the closure and pose\n"
      "  report, and optionally writes the geometry for plotting.\n"
      "  --calibrate calibrates the drive's span model from its link model's statics (or takes the\n"
      "  calibration from the cache, src/span/calibration_cache.h) and prints what it identified, its\n"
      "  cost and its cache file.\n"
      "  --span-calibration writes that calibration (from the cache, else calibrated now) to OUT.json\n"
      "  in the cache's format with its key: the file an FMU carries in resources/span_calibration.json\n"
      "  so that its span fidelity does not calibrate at instantiation (python -m harness export\n"
      "  --span-calibration).\n"
      "  --defaults prints the solver defaults of every entry point per scene and fidelity as JSON\n"
      "  (the one table, src/run/defaults.h: method, step [s], tolerance); the timing rows with the\n"
      "  steps of the drive (default: the default drive's, the table's), each with its stability\n"
      "  estimate and the reason (src/run/drive_defaults.h), and under \"drive\" its name and own row.\n"
      "  --interface prints the drive's FMU interface as JSON (src/interface/: every variable with\n"
      "  its value reference, type, unit and description, the model identifier and GUID).\n"
      "  --fmu-files writes the drive's FMU files but the binaries: DIR/modelDescription.xml and\n"
      "  DIR/resources/ with the drive and its interface table (python -m harness export adds the\n"
      "  binaries and sources).");
}

struct InfoArguments {
  std::string drive, geometry;
  bool quiet = false;
  bool defaults = false;  // print the defaults table instead
  bool calibrate = false;  // calibrate the span model and print the calibration
  std::string spanCalibration;  // and write it into this file
  bool interface = false;  // print the FMU interface
  std::string fmuFiles;    // write the FMU's model description and resources into this folder
};

// The options in any order (an option without its value is an unknown argument); -h/--help ends
// the reading. Throws std::invalid_argument for an unknown argument.
InfoArguments parseArguments(cli::Arguments& args) {
  InfoArguments r;
  while (args.next()) {
    const std::string& a = args.current();
    if (a == "--drive" && args.hasValue()) r.drive = args.value();
    else if (a == "--geometry" && args.hasValue()) r.geometry = args.value();
    else if (a == "--quiet") r.quiet = true;
    else if (a == "--defaults") r.defaults = true;
    else if (a == "--calibrate") r.calibrate = true;
    else if (a == "--span-calibration" && args.hasValue()) r.spanCalibration = args.value();
    else if (a == "--interface") r.interface = true;
    else if (a == "--fmu-files" && args.hasValue()) r.fmuFiles = args.value();
    else throw std::invalid_argument("unknown argument '" + a + "'");
  }
  return r;
}

// ---- the report ----

// The closure, the sprockets and where the pins lie.
void printReport(const Model& m) {
  std::printf("drive: %s\n", m.name.c_str());
  std::printf("links: %d, pitch %.4f mm, path length %.6f mm (n*p = %.6f mm)\n", m.chain.links, m.chain.pitch * 1e3,
              m.assembly.pathLength * 1e3, m.chain.links * m.chain.pitch * 1e3);
  std::printf("closure: %s = %.9g %s, closing-joint gap %.3e m, max joint gap %.3e m\n",
              m.assembly.closureElement.c_str(), m.assembly.closureValue,
              m.description.closure->kind == ClosureDesc::Kind::Guide ? "rad" : "m", m.assembly.closureResidual,
              m.assembly.maxJointGap);
  for (const auto& note : m.assembly.notes) std::printf("note: %s\n", note.c_str());
  for (const auto& s : m.sprockets)
    std::printf("sprocket %-16s z=%3d  pitch R %.4f mm  tip R %.4f mm  seat r %.4f mm  flank r %.3f mm  seat angle %.2f deg\n",
                s.name.c_str(), s.gap.teeth, s.gap.pitchRadius * 1e3, s.gap.tipRadius * 1e3, s.gap.seatRadius * 1e3,
                s.gap.flankRadius * 1e3, s.gap.seatAngle * 180.0 / kPi);
  int onS = 0, onG = 0, onF = 0;
  for (const auto& p : m.pins) (p.on == PinNominal::On::Sprocket ? onS : p.on == PinNominal::On::Guide ? onG : onF)++;
  std::printf("pins: %d on sprockets, %d on guides, %d in free spans\n", onS, onG, onF);
  std::printf("states: %d\n", m.nStates);
}

// ---- the geometry (all in the drawn pose: rotors at their initial angles) ----

void addSprockets(const Model& m, nlohmann::json& g) {
  for (const auto& s : m.sprockets) {
    nlohmann::json js;
    js["name"] = s.name;
    js["center"] = {s.center.x, s.center.y};
    js["pitchRadius"] = s.gap.pitchRadius;
    js["tipRadius"] = s.gap.tipRadius;
    const double a0 = m.rotors[s.rotor].initialAngle;
    for (const auto& p : s.gap.outline(6)) {
      const Vec2 q = s.center + rotate(p, a0);
      js["outline"].push_back({q.x, q.y});
    }
    g["sprockets"].push_back(js);
  }
}

// A guide face as points: the two ends of a line, 41 points along an arc; turned by the guide's angle a.
nlohmann::json facePoints(const GuideFace& f, Vec2 pivot, double a) {
  nlohmann::json pts;
  if (f.type == GuideFace::Type::Line) {
    for (Vec2 p : {f.from, f.to}) {
      const Vec2 q = pivot + rotate(p - pivot, a);
      pts.push_back({q.x, q.y});
    }
  } else {
    double a0 = angleOf(f.arc.dir0), a1 = angleOf(f.arc.dir1);
    while (a1 < a0) a1 += 2.0 * kPi;
    for (int k = 0; k <= 40; ++k) {
      const Vec2 p = f.arc.center + f.arc.radius * unit(a0 + (a1 - a0) * k / 40.0);
      const Vec2 q = pivot + rotate(p - pivot, a);
      pts.push_back({q.x, q.y});
    }
  }
  return pts;
}

void addGuides(const Model& m, nlohmann::json& g) {
  for (const auto& gm : m.guides) {
    nlohmann::json jg;
    jg["name"] = gm.name;
    jg["pivot"] = {gm.pivot.x, gm.pivot.y};
    jg["pivoting"] = gm.rotor >= 0;
    const double a = gm.rotor >= 0 ? m.rotors[gm.rotor].initialAngle : 0.0;
    for (const auto& f : gm.faces) jg["faces"].push_back(facePoints(f, gm.pivot, a));
    g["guides"].push_back(jg);
  }
}

// The chain path: its segments (wraps and spans), 2001 points along it, the span force probes.
void addChainPath(const Model& m, nlohmann::json& g) {
  for (const auto& p : m.pins) g["pins"].push_back({p.position.x, p.position.y});
  for (const auto& seg : m.path.segments()) {
    const std::string& from = m.description.chain.route[seg.routeIndex];
    const std::string& to = m.description.chain.route[(seg.routeIndex + 1) % m.description.chain.route.size()];
    g["segments"].push_back({{"kind", seg.isArc ? "wrap" : "span"},
                             {"element", seg.isArc ? from : from + " -> " + to},
                             {"start", seg.start},
                             {"length", seg.length}});
  }
  g["pathLength"] = m.path.length();
  for (int k = 0; k <= 2000; ++k) {
    const Vec2 q = m.path.point(m.path.length() * k / 2000.0);
    g["path"].push_back({q.x, q.y});
  }
  for (const auto* sp : {&m.tightSpan, &m.slackSpan})
    g["probes"].push_back(sp->present ? nlohmann::json{sp->point.x, sp->point.y} : nlohmann::json());
}

void writeGeometry(const Model& m, const std::string& path) {
  nlohmann::json g;
  g["name"] = m.name;
  g["pitch"] = m.chain.pitch;
  g["rollerRadius"] = m.chain.rollerRadius;
  g["plateHalfHeight"] = m.chain.plateHalfHeight;
  addSprockets(m, g);
  addGuides(m, g);
  if (m.tensioner.present) {
    const int r = m.tensioner.rotor;
    const Vec2 pad = m.rotors[r].axis + rotate(m.tensioner.pad - m.rotors[r].axis, m.rotors[r].initialAngle);
    g["tensioner"] = {{"housing", {m.tensioner.housing.x, m.tensioner.housing.y}},
                      {"pad", {pad.x, pad.y}},
                      {"direction", {m.tensioner.direction.x, m.tensioner.direction.y}}};
  }
  addChainPath(m, g);
  g["closure"] = {{"element", m.assembly.closureElement}, {"value", m.assembly.closureValue}};
  std::ofstream(path) << g.dump(1) << "\n";
}

// The span model's calibration: its notes (laws, residuals, cost, cache file), and the file it
// is written to when `out` names one.
void printCalibration(const Model& m, const std::string& out) {
  span::SpanModel sm = span::assembleSpanModel(m, false);
  const double wall0 = static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
  bool fromCache = false;
  std::string file;
  if (out.empty()) span::calibrateSpanModel(sm, &fromCache, &file);
  else fromCache = span::writeCalibrationFile(sm, out) == span::CalibrationOrigin::Cache;
  // the spans' damping where the drive asks for it identified (run/span_damping.h)
  if (m.description.spanModel.damping == SpanModelDesc::Source::Identified)
    calibrateSpanDamping(std::shared_ptr<const Model>(&m, [](const Model*) {}), sm);
  const double cpu = static_cast<double>(std::clock()) / CLOCKS_PER_SEC - wall0;
  for (const std::string& note : sm.notes)
    if (note.rfind("calibration: ", 0) == 0) std::printf("%s\n", note.c_str());
  std::printf("calibration: this call took %.2f s CPU (%s)\n", cpu, fromCache ? "read from the cache" : "identified");
}

// A row as JSON: method, step_s, tolerance; a timing row with the drive's step adds its division
// of kStepInterval, the stability estimate [s] and the estimate's division, the default drive's
// margin, the probe where it ran, and the reason.
nlohmann::json rowJson(const DriveRow& r) {
  nlohmann::json j = {{"method", choiceName(r.row.method)}, {"step_s", r.row.step}, {"tolerance", r.row.tolerance}};
  if (r.divisions > 0) {
    j["divisions"] = r.divisions;
    j["estimate_s"] = r.estimate;
    j["estimateDivisions"] = r.estimateDivisions;
    j["margin"] = r.margin;
    j["limitedBy"] = r.limitedBy;
  }
  if (r.probe) j["probe"] = probeJson(*r.probe);  // (run/step_probe.h)
  j["reason"] = r.reason;
  return j;
}

// The defaults table as {scene: {fidelity: {method, step_s, tolerance, ...}}}, a row for runs with
// joints with clearance or rigid contacts under its fidelity's as "clearanceOrRigid"; the timing
// rows with the steps of the drive (the default drive's: the table's own), and under "drive" its
// name, whether its joints have clearance or its contacts are rigid, and its own link row's key.
// A drive without a span model has no span row (its reason under "drive").
void printDefaults(const InfoArguments& a) {
  const DriveDescription desc = cli::loadDrive(a.drive);
  const Model m = assemble(desc);
  nlohmann::json table = nlohmann::json::object();
  nlohmann::json drive = {{"name", m.name}};
  for (const bool clearanceOrRigid : {false, true})
    for (const SolverDefaults& row : kSolverDefaults) {
      if (row.clearanceOrRigid != clearanceOrRigid) continue;
      DriveRow r;
      try {
        r = driveRow(m, row);
      } catch (const DescriptionError& e) {  // (no span model)
        drive["noSpanModel"] = e.what();
        continue;
      }
      nlohmann::json& at = table[choiceName(row.scene)][choiceName(row.fidelity)];
      (clearanceOrRigid ? at["clearanceOrRigid"] : at) = rowJson(r);
    }
  SimulationOptions opt;
  drive["clearanceOrRigid"] = ownTableRow(m, opt).clearanceOrRigid;
  if (!a.drive.empty()) {
    drive["file"] = a.drive;
    table["drive"] = drive;
  }
  std::printf("%s\n", table.dump(1).c_str());
}

// The FMU interface of the drive: printed, or written as the FMU's files (the drive's text as
// given; the default drive's embedded text).
int writeInterface(const InfoArguments& r) {
  // (the description read first: its problems name the file)
  const DriveInterface di = driveInterface(cli::loadDrive(r.drive));
  if (!r.fmuFiles.empty())
    writeFmuFiles(r.fmuFiles, r.drive.empty() ? std::string(defaultDriveJson()) : readDescriptionFile(r.drive));
  if (r.interface) std::printf("%s\n", interfaceJson(di).dump(1).c_str());
  else std::printf("%s: %s.fmu, GUID %s, %zu variables\n", r.fmuFiles.c_str(), di.modelIdentifier.c_str(),
                   di.guid.c_str(), di.variables.size());
  return 0;
}

int run(const InfoArguments& r) {
  if (r.defaults) {
    printDefaults(r);
    return 0;
  }
  if (r.interface || !r.fmuFiles.empty()) return writeInterface(r);
  const DriveDescription desc = cli::loadDrive(r.drive);
  const Model m = assemble(desc);
  if (!r.quiet) printReport(m);
  if (!r.geometry.empty()) writeGeometry(m, r.geometry);
  if (r.calibrate || !r.spanCalibration.empty()) printCalibration(m, r.spanCalibration);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::runTool(kTool, argc, argv, usage, parseArguments, run);
}
