#include "io/openfoam_export.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>

#include "cfd/gas_solver.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/steps.hpp"
#include "core/text_format.hpp"
#include "dem/particles.hpp"
#include "dem/walls.hpp"
#include "run/packed_bed.hpp"
#include "sim/placement.hpp"

namespace fluidbed {
namespace {

// Numbers as the shortest text that reads back as the same double: the files hold exactly the
// scene's numbers.
std::string num(double v) { return shortest_number(v); }

// Three significant digits, for the notes.
std::string g3(double v) { return format_number("%.3g", v); }

const char* kBanner =
    "/*--------------------------------*- C++ -*----------------------------------*\\\n"
    "  OpenFOAM v1912 case written by `fluidbed export SCENE --to openfoam DIR`\n"
    "\\*---------------------------------------------------------------------------*/\n";

std::string foam_header(const std::string& cls, const std::string& location,
                        const std::string& object) {
  std::string h = kBanner;
  h += "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       " + cls + ";\n";
  if (!location.empty()) h += "    location    \"" + location + "\";\n";
  h += "    object      " + object + ";\n}\n\n";
  return h;
}

// One list item of a header comment, wrapped at 96 characters.
void comment_item(std::ostream& out, const std::string& text, const char* lead = "//  - ") {
  std::istringstream words(text);
  std::string line = lead;
  std::string cont = lead;  // the lead with its dash blanked: "//    ", "#    "
  if (const auto dash = cont.find('-'); dash != std::string::npos) cont[dash] = ' ';
  bool first = true;
  for (std::string w; words >> w;) {
    if (!first && line.size() + 1 + w.size() > 96) {
      out << line << '\n';
      line = cont;
      first = true;
    }
    line += (first ? "" : " ") + w;
    first = false;
  }
  out << line << '\n';
}

// The x extents of the mesh blocks along the bottom and which patch each bottom belongs to.
struct Segment {
  double x0, x1;  // m
  int cells;
  bool inlet;
};

struct Mesh {
  std::vector<Segment> segments;
  bool uniform_cells = true;  // every cell dx wide, as the scene's grid
  bool thick = false;         // a slab the spheres move through (slab_has_depth): walls front
                              // and back; otherwise empty patches, the spheres on the mid-plane
};

Mesh mesh_for(const Settings& s) {
  const int nx = s.gas.cells_x;
  const double w = s.domain.width, dx = w / nx;
  Mesh m;
  m.thick = slab_has_depth(s.domain, s.particles.diameter);
  if (s.inlet.kind != InletKind::Jet) {
    m.segments.push_back({0.0, w, nx, s.inlet.kind == InletKind::Uniform});
    return m;
  }
  const double x0 = 0.5 * (w - s.inlet.jet_width), x1 = 0.5 * (w + s.inlet.jet_width);
  const double side = x0 / dx;
  int n_side = static_cast<int>(std::lround(side));
  n_side = std::clamp(n_side, 1, (nx - 1) / 2);  // at least one cell each side and in the slot
  m.uniform_cells = std::fabs(side - n_side) < 1e-9 * std::max(1.0, side) && nx - 2 * n_side >= 1;
  m.segments.push_back({0.0, x0, n_side, false});
  m.segments.push_back({x0, x1, nx - 2 * n_side, true});
  m.segments.push_back({x1, w, n_side, false});
  return m;
}

double inlet_velocity(const Settings& s) {
  if (s.inlet.kind == InletKind::Jet)  // one jet (write_openfoam_case refuses more)
    return jet_slot_velocity(s.inlet.superficial_velocity, s.domain.width, s.inlet.jets,
                             s.inlet.jet_width);
  if (s.inlet.kind == InletKind::Uniform) return s.inlet.superficial_velocity;
  return 0.0;
}

void write_block_mesh(std::ostream& out, const Settings& s, const Mesh& m) {
  out << foam_header("dictionary", "system", "blockMeshDict");
  out << "// The bed: x across (0 to " << num(s.domain.width) << " m), y up (0 to "
      << num(s.domain.height) << " m), z through the slab (0 to " << num(s.domain.thickness)
      << " m),\n// one cell deep: the scene's gas grid of " << s.gas.cells_x << " x "
      << s.gas.cells_y << " cells";
  if (s.inlet.kind == InletKind::Jet) out << ", in three blocks so that the jet slot is a patch of its own";
  out << ".\n\nscale 1;\n\nvertices\n(\n";
  // Vertex 4 i + 2 z + y: x = the i-th block edge, y in {0, H}, z in {0, T}.
  std::vector<double> xs = {m.segments.front().x0};
  for (const Segment& g : m.segments) xs.push_back(g.x1);
  for (std::size_t i = 0; i < xs.size(); ++i)
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y)
        out << "    (" << num(xs[i]) << ' ' << (y ? num(s.domain.height) : "0") << ' '
            << (z ? num(s.domain.thickness) : "0") << ")\n";
  out << ");\n\n";
  auto v = [](std::size_t i, int y, int z) { return 4 * i + 2 * static_cast<std::size_t>(z) + y; };
  out << "blocks\n(\n";
  for (std::size_t i = 0; i < m.segments.size(); ++i)
    out << "    hex (" << v(i, 0, 0) << ' ' << v(i + 1, 0, 0) << ' ' << v(i + 1, 1, 0) << ' '
        << v(i, 1, 0) << ' ' << v(i, 0, 1) << ' ' << v(i + 1, 0, 1) << ' ' << v(i + 1, 1, 1) << ' '
        << v(i, 1, 1) << ") (" << m.segments[i].cells << ' ' << s.gas.cells_y
        << " 1) simpleGrading (1 1 1)\n";
  out << ");\n\nedges\n(\n);\n\n";
  // Faces listed with their outward normal by the right-hand rule.
  auto bottom = [&](std::size_t i) {
    std::ostringstream f;
    f << "            (" << v(i, 0, 0) << ' ' << v(i + 1, 0, 0) << ' ' << v(i + 1, 0, 1) << ' '
      << v(i, 0, 1) << ")\n";
    return f.str();
  };
  const std::size_t last = m.segments.size();
  out << "boundary\n(\n";
  bool has_inlet = false;
  for (const Segment& g : m.segments) has_inlet = has_inlet || g.inlet;
  if (has_inlet) {
    out << "    inlet   // the gas enters here; a wall for the particles, as in fluidbed\n"
        << "    {\n        type wall;\n        faces\n        (\n";
    for (std::size_t i = 0; i < last; ++i)
      if (m.segments[i].inlet) out << bottom(i);
    out << "        );\n    }\n";
  }
  bool has_bottom = false;
  for (const Segment& g : m.segments) has_bottom = has_bottom || !g.inlet;
  if (has_bottom) {
    out << "    bottom\n    {\n        type wall;\n        faces\n        (\n";
    for (std::size_t i = 0; i < last; ++i)
      if (!m.segments[i].inlet) out << bottom(i);
    out << "        );\n    }\n";
  }
  out << "    walls\n    {\n        type wall;\n        faces\n        (\n";
  out << "            (" << v(0, 0, 0) << ' ' << v(0, 0, 1) << ' ' << v(0, 1, 1) << ' '
      << v(0, 1, 0) << ")\n";
  out << "            (" << v(last, 0, 0) << ' ' << v(last, 1, 0) << ' ' << v(last, 1, 1) << ' '
      << v(last, 0, 1) << ")\n";
  out << "        );\n    }\n";
  out << "    outlet  // the gas leaves at the top; "
      << (s.domain.top_wall ? "a wall for the particles (domain.top_wall)"
                            : "a particle that reaches it leaves the case")
      << "\n    {\n        type " << (s.domain.top_wall ? "wall" : "patch")
      << ";\n        faces\n        (\n";
  for (std::size_t i = 0; i < last; ++i)
    out << "            (" << v(i, 1, 0) << ' ' << v(i, 1, 1) << ' ' << v(i + 1, 1, 1) << ' '
        << v(i + 1, 1, 0) << ")\n";
  out << "        );\n    }\n";
  if (m.thick)
    out << "    frontAndBack  // the slab's front and back: walls for the spheres, slip for the "
           "gas (see\n                  // kinematicCloudProperties)\n    {\n        type wall;"
           "\n        faces\n        (\n";
  else
    out << "    frontAndBack  // the pseudo-2-D slab: no front or back walls (see "
           "kinematicCloudProperties)\n    {\n        type empty;\n        faces\n        (\n";
  for (std::size_t i = 0; i < last; ++i) {
    out << "            (" << v(i, 0, 0) << ' ' << v(i, 1, 0) << ' ' << v(i + 1, 1, 0) << ' '
        << v(i + 1, 0, 0) << ")\n";
    out << "            (" << v(i, 0, 1) << ' ' << v(i + 1, 0, 1) << ' ' << v(i + 1, 1, 1) << ' '
        << v(i, 1, 1) << ")\n";
  }
  out << "        );\n    }\n);\n\nmergePatchPairs\n(\n);\n";
}

// Steps between writes: about the frame interval of fluidbed's VTK output (0.04 s), or the whole
// run when shorter, always a divisor of the run so that the last step is written.
std::int64_t write_every(const Settings& s) {
  const std::int64_t total = std::max<std::int64_t>(1, steps_for(s.time.end, s.time.dt));
  std::int64_t every = std::max<std::int64_t>(1, steps_for(0.04, s.time.dt));
  if (every >= total) return total;
  // A divisor of the run length near the interval, so that the end is a write time.
  // (OpenFOAM writes only at write steps, not at endTime as such.) None: the end alone.
  for (std::int64_t e = every; e <= 2 * every && e <= total; ++e)
    if (total % e == 0) return e;
  return total;
}

void write_control(std::ostream& out, const Settings& s) {
  const std::int64_t steps = steps_for(s.time.end, s.time.dt);
  out << foam_header("dictionary", "system", "controlDict");
  out << "// The scene's time step and run length: " << steps << " steps of " << num(s.time.dt)
      << " s to " << num(s.time.end) << " s.\n\n";
  // startTime, not latestTime: a case exported again into the same folder starts afresh.
  out << "application     DPMFoam;\n\nstartFrom       startTime;\n\nstartTime       0;\n\n"
      << "stopAt          endTime;\n\n";
  out << "endTime         " << num(static_cast<double>(steps) * s.time.dt) << ";\n\n";
  out << "deltaT          " << num(s.time.dt) << ";\n\n";
  out << "writeControl    timeStep;\n\nwriteInterval   " << write_every(s) << ";   // steps\n\n";
  out << "purgeWrite      0;\n\nwriteFormat     ascii;\n\nwritePrecision  10;\n\n"
      << "writeCompression off;\n\ntimeFormat      general;\n\ntimePrecision   10;\n\n"
      << "runTimeModifiable false;\n\nadjustTimeStep  no;\n";
}

void write_schemes(std::ostream& out) {
  out << foam_header("dictionary", "system", "fvSchemes");
  out << "// fluidbed: first-order upwind convection (as here), Crank-Nicolson in time (Euler "
         "here:\n// DPMFoam's coupling source terms are first order in time anyway).\n\n";
  out << "ddtSchemes\n{\n    default         Euler;\n}\n\n"
      << "gradSchemes\n{\n    default         Gauss linear;\n}\n\n"
      << "divSchemes\n{\n    default         none;\n"
      << "    div(alphaPhi.air,U.air)    Gauss upwind;\n"
      << "    div(((alpha.air*nuEff.air)*dev2(T(grad(U.air))))) Gauss linear;\n}\n\n"
      << "laplacianSchemes\n{\n    default         Gauss linear corrected;\n}\n\n"
      << "interpolationSchemes\n{\n    default         linear;\n}\n\n"
      << "snGradSchemes\n{\n    default         corrected;\n}\n";
}

void write_solution(std::ostream& out, const Settings& s) {
  out << foam_header("dictionary", "system", "fvSolution");
  out << "solvers\n{\n"
      << "    \"(p|kinematicCloud:theta)\"\n    {\n        solver          GAMG;\n"
      << "        tolerance       1e-06;\n        relTol          0.01;\n"
      << "        smoother        GaussSeidel;\n    }\n\n"
      << "    \"(p|kinematicCloud:theta)Final\"\n    {\n        solver          GAMG;\n"
      << "        tolerance       1e-06;\n        relTol          0;\n"
      << "        smoother        GaussSeidel;\n    }\n\n"
      << "    \"U.air.*\"\n    {\n        solver          smoothSolver;\n"
      << "        smoother        symGaussSeidel;\n        tolerance       1e-06;\n"
      << "        relTol          0;\n    }\n}\n\n";
  out << "PIMPLE\n{\n    nOuterCorrectors 1;\n    nCorrectors     2;\n"
      << "    momentumPredictor yes;\n    nNonOrthogonalCorrectors 0;\n";
  if (s.inlet.kind == InletKind::None) out << "    pRefCell        0;\n    pRefValue       0;\n";
  out << "}\n\nrelaxationFactors\n{\n}\n";
}

void write_decompose(std::ostream& out) {
  out << foam_header("dictionary", "system", "decomposeParDict");
  out << "// Two sub-domains side by side (x): the bed and its jet are symmetric, so each holds\n"
      << "// about half the particles. Never cut in z (one cell).\n\n";
  out << "numberOfSubdomains 2;\n\nmethod          simple;\n\n"
      << "coeffs\n{\n    n               (2 1 1);\n}\n";
}

void write_gravity(std::ostream& out, const Settings& s) {
  out << foam_header("uniformDimensionedVectorField", "constant", "g");
  out << "dimensions      [0 1 -2 0 0 0 0];\nvalue           (0 " << num(-s.physics.gravity)
      << " 0);\n";
}

void write_transport(std::ostream& out, const Settings& s) {
  out << foam_header("dictionary", "constant", "transportProperties");
  out << "// Air: density " << num(s.gas.density) << " kg/m^3, viscosity " << num(s.gas.viscosity)
      << " Pa s (nu = mu / rho).\n\n";
  out << "continuousPhase air;\n\nrho.air         " << num(s.gas.density) << ";\n\n"
      << "transportModel  Newtonian;\n\nnu              " << num(s.gas.viscosity / s.gas.density)
      << ";\n";
}

void write_turbulence(std::ostream& out) {
  out << foam_header("dictionary", "constant", "turbulenceProperties.air");
  out << "// fluidbed's gas has no turbulence model (the cells are 2.5 x 5 diameters).\n\n"
      << "simulationType  laminar;\n";
}

void write_pressure(std::ostream& out, const Mesh& m) {
  out << foam_header("volScalarField", "0", "p");
  out << "// Kinematic pressure (p / rho), relative to the exit.\n\n";
  out << "dimensions      [0 2 -2 0 0 0 0];\n\ninternalField   uniform 0;\n\nboundaryField\n{\n";
  bool inlet = false, bottom = false;
  for (const Segment& g : m.segments) (g.inlet ? inlet : bottom) = true;
  if (inlet)
    out << "    inlet\n    {\n        type            fixedFluxPressure;\n        value           "
           "$internalField;\n    }\n";
  if (bottom)
    out << "    bottom\n    {\n        type            fixedFluxPressure;\n        value           "
           "$internalField;\n    }\n";
  out << "    walls\n    {\n        type            fixedFluxPressure;\n        value           "
         "$internalField;\n    }\n";
  out << "    outlet\n    {\n        type            fixedValue;\n        value           "
         "$internalField;\n    }\n";
  if (m.thick)
    out << "    frontAndBack\n    {\n        type            fixedFluxPressure;\n"
           "        value           $internalField;\n    }\n}\n";
  else
    out << "    frontAndBack\n    {\n        type            empty;\n    }\n}\n";
}

void write_velocity(std::ostream& out, const Settings& s, const Mesh& m) {
  const double u = inlet_velocity(s);
  out << foam_header("volVectorField", "0", "U.air");
  out << "// Interstitial gas velocity. The inlet gives the superficial (plug) velocity ";
  if (s.inlet.kind == InletKind::Jet)
    out << "of the jet,\n// U W / jet_width = " << num(s.inlet.superficial_velocity) << " x "
        << num(s.domain.width) << " / " << num(s.inlet.jet_width) << " = " << num(u) << " m/s";
  else
    out << "of the distributor,\n// " << num(u) << " m/s";
  out << " (fluidbed: porosity 1 at the inlet face).\n\n";
  out << "dimensions      [0 1 -1 0 0 0 0];\n\ninternalField   uniform (0 0 "
         "0);\n\nboundaryField\n{\n";
  bool inlet = false, bottom = false;
  for (const Segment& g : m.segments) (g.inlet ? inlet : bottom) = true;
  if (inlet)
    out << "    inlet\n    {\n        type            interstitialInletVelocity;\n"
        << "        inletVelocity   uniform (0 " << num(u) << " 0);\n"
        << "        value           uniform (0 " << num(u) << " 0);\n"
        << "        phi             phi.air;\n        alpha           alpha.air;\n    }\n";
  if (bottom) out << "    bottom\n    {\n        type            noSlip;\n    }\n";
  out << "    walls\n    {\n        type            noSlip;\n    }\n";
  out << "    outlet\n    {\n        type            pressureInletOutletVelocity;\n"
      << "        phi             phi.air;\n        inletValue      uniform (0 0 0);\n"
      << "        value           uniform (0 0 0);\n    }\n";
  // fluidbed's gas is averaged through the depth (eq 23): no shear at the front and back.
  out << "    frontAndBack\n    {\n        type            " << (m.thick ? "slip" : "empty")
      << ";\n    }\n}\n";
}

void write_positions(std::ostream& out, const Settings& s, const Mesh& m, const Particles& p) {
  out << foam_header("vectorField", "constant", "kinematicCloudPositions");
  out << "// The scene's start (particles.placement = \"" << option_name(s.particles.placement)
      << "\"), one sphere per line, x y z (m); z is "
      << (m.thick ? "the depth in the slab" : "the slab's mid-plane") << ".\n\n";
  out << p.size() << "\n(\n";
  const std::string mid = num(0.5 * s.domain.thickness);
  for (std::size_t i = 0; i < p.size(); ++i)
    out << '(' << num(p.x[i]) << ' ' << num(p.y[i]) << ' ' << (m.thick ? num(p.z[i]) : mid)
        << ")\n";
  out << ")\n";
}

void write_cloud(std::ostream& out, const Settings& s, const DpmCollisionLaw& law,
                 const std::vector<std::string>& notes) {
  out << foam_header("dictionary", "constant", "kinematicCloudProperties");
  out << "// The particles of the fluidbed scene \"" << s.scene.name << "\": " << s.particles.count
      << " spheres of " << num(s.particles.diameter) << " m, " << num(s.particles.density)
      << " kg/m^3,\n// each parcel one sphere (nParticle 1). What differs from fluidbed:\n";
  for (const std::string& n : notes) comment_item(out, n);
  out << "\nsolution\n{\n    active          true;\n    coupled         true;\n"
      << "    transient       yes;\n    cellValueSourceCorrection off;\n\n"
      << "    // fluidbed takes the gas of the cell holding the centre: \"cell\".\n"
      << "    interpolationSchemes\n    {\n        rho.air         cell;\n"
      << "        U.air           cell;\n        mu.air          cell;\n    }\n\n"
      << "    integrationSchemes\n    {\n        U               Euler;\n    }\n\n"
      << "    sourceTerms\n    {\n        schemes\n        {\n"
      << "            U               semiImplicit 1;\n        }\n    }\n}\n\n";
  out << "constantProperties\n{\n    parcelTypeId    1;\n\n    rhoMin          1e-15;\n"
      << "    minParcelMass   1e-15;\n\n    rho0            " << num(s.particles.density)
      << ";   // kg/m^3\n"
      << "    youngsModulus   " << num(law.youngs_modulus)
      << ";   // Pa: (4/3) sqrt(d/4) E / (2 (1 - nu^2)) = kappa_n = " << num(law.kn_pair)
      << " N/m\n"
      << "    poissonsRatio   " << num(law.poissons_ratio) << ";\n\n"
      << "    constantVolume  false;\n\n    alphaMax        0.99;\n}\n\n";
  out << "subModels\n{\n    particleForces\n    {\n"
      << "        // Wen & Yu: the closest to fluidbed's Di Felice drag (see the header).\n"
      << "        WenYuDrag\n        {\n            alphac alpha.air;\n        }\n"
      << "        gravity;\n    }\n\n";
  out << "    injectionModels\n    {\n        start\n        {\n"
      << "            type            manualInjection;\n            massTotal       0;\n"
      << "            parcelBasisType fixed;\n            nParticle       1;\n"
      << "            SOI             0;\n            positionsFile   "
         "\"kinematicCloudPositions\";\n"
      << "            U0              (0 0 0);\n            sizeDistribution\n            {\n"
      << "                type        fixedValue;\n                fixedValueDistribution\n"
      << "                {\n                    value   " << num(s.particles.diameter)
      << ";\n                }\n            }\n        }\n    }\n\n";
  out << "    dispersionModel none;\n\n"
      << "    // Only used if a centre ever crosses a wall face (the spring model acts first).\n"
      << "    patchInteractionModel standardWallInteraction;\n\n"
      << "    standardWallInteractionCoeffs\n    {\n        type            rebound;\n"
      << "        e               " << num(law.restitution_wall) << ";\n"
      << "        mu              " << num(law.mu) << ";\n    }\n\n"
      << "    heatTransferModel none;\n\n    surfaceFilmModel none;\n\n"
      << "    collisionModel  pairCollision;\n\n";
  out << "    pairCollisionCoeffs\n    {\n        maxInteractionDistance  "
      << num(s.particles.diameter) << ";\n\n        writeReferredParticleCloud no;\n\n"
      << "        pairModel pairSpringSliderDashpot;\n\n"
      << "        pairSpringSliderDashpotCoeffs\n        {\n"
      << "            useEquivalentSize   no;\n"
      << "            alpha               " << num(law.alpha_pair) << ";   // restitution "
      << g3(law.restitution_pair) << " at " << num(law.reference_speed) << " m/s\n"
      << "            b                   " << num(law.b) << ";   // a linear spring\n"
      << "            mu                  " << num(law.mu) << ";\n"
      << "            cohesionEnergyDensity 0;\n"
      << "            collisionResolutionSteps " << law.resolution_steps
      << ";   // our steps per contact: no sub-cycling\n        }\n\n"
      << "        wallModel wallSpringSliderDashpot;\n\n"
      << "        wallSpringSliderDashpotCoeffs\n        {\n"
      << "            useEquivalentSize   no;\n"
      << "            collisionResolutionSteps " << law.resolution_steps << ";\n"
      << "            youngsModulus       " << num(law.wall_youngs_modulus)
      << ";   // Pa: wall kN = kappa_n = " << num(law.kn_wall) << " N/m\n"
      << "            poissonsRatio       " << num(law.wall_poissons_ratio) << ";\n"
      << "            alpha               " << num(law.alpha_wall) << ";   // restitution "
      << g3(law.restitution_wall) << " at " << num(law.reference_speed) << " m/s\n"
      << "            b                   " << num(law.b) << ";\n"
      << "            mu                  " << num(law.mu) << ";\n"
      << "            cohesionEnergyDensity 0;\n        }\n\n"
      << "        U               U.air;\n    }\n\n"
      << "    stochasticCollisionModel none;\n\n    radiation       off;\n}\n\n"
      << "cloudFunctions\n{\n}\n";
}

void write_allrun(std::ostream& out, const Settings& s, const std::vector<std::string>& notes) {
  out << "#!/bin/sh\n";
  out << "# DPMFoam case of the fluidbed scene \"" << s.scene.name
      << "\" (OpenFOAM v1912, Debian's `openfoam` package).\n";
  out << "#   ./Allrun          blockMesh, decomposePar, mpirun -np 2 DPMFoam -parallel, "
         "reconstructPar\n";
  out << "#   ./Allrun serial   blockMesh, DPMFoam on one process\n";
  out << "# Logs: log.blockMesh, log.decomposePar, log.DPMFoam, log.reconstructPar. Results: one "
         "folder per\n# written time, particles in TIME/lagrangian/kinematicCloud/.\n#\n";
  out << "# What differs from fluidbed:\n";
  for (const std::string& n : notes) comment_item(out, n, "#  - ");
  out << "cd \"${0%/*}\" || exit 1\n\n";
  out << "# OpenFOAM's environment. Debian's package puts the programs in /usr/bin and needs only\n"
      << "# WM_PROJECT_DIR (its etc/bashrc looks for tools the package leaves out); an upstream\n"
      << "# installation is set up by sourcing its etc/bashrc.\n";
  out << "if ! command -v DPMFoam > /dev/null 2>&1; then\n"
      << "    for rc in /usr/lib/openfoam/openfoam*/etc/bashrc /opt/openfoam*/etc/bashrc; do\n"
      << "        if [ -f \"$rc\" ]; then . \"$rc\"; break; fi\n    done\nfi\n"
      << "if [ -z \"$WM_PROJECT_DIR\" ] && [ -f /usr/share/openfoam/etc/controlDict ]; then\n"
      << "    WM_PROJECT_DIR=/usr/share/openfoam; export WM_PROJECT_DIR\nfi\n"
      << "if ! command -v DPMFoam > /dev/null 2>&1; then\n"
      << "    echo \"Allrun: DPMFoam not found (Debian: apt-get install openfoam)\" >&2; exit 2\n"
      << "fi\n\n";
  out << "run() {  # run NAME COMMAND...: the command's output in log.NAME; stop on failure\n"
      << "    name=$1; shift\n    echo \"running $name\"\n"
      << "    if ! \"$@\" > \"log.$name\" 2>&1; then\n"
      << "        echo \"Allrun: $name failed, see log.$name\" >&2; tail -20 \"log.$name\" >&2; "
         "exit 1\n"
      << "    fi\n}\n\n";
  out << "run blockMesh blockMesh\n";
  out << "if [ \"$1\" = serial ]; then\n    run DPMFoam DPMFoam\n    exit 0\nfi\n";
  out << "run decomposePar decomposePar -force\n";
  out << "# Open MPI refuses root unless told; --oversubscribe lets 2 processes share 1 core.\n"
      << "mpi_flags=\"--oversubscribe\"\n"
      << "if [ \"$(id -u)\" -eq 0 ]; then mpi_flags=\"$mpi_flags --allow-run-as-root\"; fi\n";
  out << "run DPMFoam mpirun $mpi_flags -np 2 DPMFoam -parallel\n";
  out << "run reconstructPar reconstructPar\n";
}

Particles start_particles(const Settings& s,
                          const std::function<void(const std::string&)>& notify) {
  switch (s.particles.placement) {
    case Placement::Lattice:
    case Placement::Single: return place_particles(s);
    case Placement::State: return load_scene_state(s).particles;
    case Placement::Packed: {
      Settings from = s;
      from.particles.state_file = packed_bed_state(s, notify);
      return load_scene_state(from).particles;
    }
  }
  throw InputError("particles.placement \"" + option_string(s.particles.placement) +
                   "\": the OpenFOAM export knows lattice, single, state and packed");
}

std::vector<std::string> notes_for(const Settings& s, const DpmCollisionLaw& law, const Mesh& m,
                                   const Particles& p) {
  std::vector<std::string> n;
  n.push_back(
      "contact law: the normal spring is fluidbed's (b = 1, kN = " + g3(law.kn_pair) +
      " N/m for pairs and walls, from E = " + g3(law.youngs_modulus) +
      " Pa, E_wall = " + g3(law.wall_youngs_modulus) + " Pa, nu = " + num(law.poissons_ratio) +
      "); its dashpot grows as overlap^(1/4) where fluidbed's is constant (eta = " +
      num(s.contact.damping) + " kg/s): alpha = " + g3(law.alpha_pair) + " (pairs), " +
      g3(law.alpha_wall) + " (walls) give fluidbed's restitution " + g3(law.restitution_pair) +
      " (pairs), " + g3(law.restitution_wall) + " (walls) for a head-on impact at " +
      num(law.reference_speed) + " m/s; a pair's restitution is " + g3(law.restitution_pair_slow) +
      " at " + num(law.slow_speed) + " m/s and " + g3(law.restitution_pair_fast) + " at " +
      num(law.fast_speed) + " m/s");
  n.push_back("contact law, tangential: DPMFoam's spring is Mindlin's, 8 G* sqrt(R* overlap), " +
              g3(law.kt_pair) + " N/m at the peak overlap of a " + num(law.reference_speed) +
              " m/s impact (" + g3(law.peak_overlap_pair) + " m) against fluidbed's " +
              g3(s.contact.stiffness * s.contact.tangential_stiffness_ratio) +
              " N/m; its tangential dashpot is the normal one (fluidbed: " +
              num(s.contact.tangential_damping_ratio) +
              " times it); Coulomb's limit mu = " + num(law.mu) +
              " caps the tangential force at mu times the whole normal force, dashpot included "
              "(fluidbed: the spring force); a sliding pair's spring restarts from zero (fluidbed "
              "holds it at the limit); the wall model keeps no tangential spring between steps");
  n.push_back(
      "collisions: DPMFoam integrates them with its own velocity-Verlet scheme and the "
      "geometric overlap (fluidbed: \"" +
      option_string(s.time.integrator) + "\", \"" + option_string(s.contact.displacement) +
      "\" overlaps); collisionResolutionSteps = " + std::to_string(law.resolution_steps) +
      " (fluidbed's steps per contact) keeps DPMFoam from sub-cycling the scene's dt");
  const double eps = 0.42, u_mf = 1.9;
  n.push_back(
      "drag: WenYuDrag, the closest of DPMFoam's models to fluidbed's Di Felice: both are "
      "the single-sphere drag times a power of the porosity (Wen-Yu: Schiller-Naumann "
      "C_d, eps^-2.65; Di Felice: Dallavalle C_d, eps^(1 - chi), chi = 3.7 - 0.65 "
      "exp(...), 2.05-2.7); ErgunWenYuDrag switches to Ergun below eps = 0.8, "
      "PlessisMasliyahDrag is a permeability law. DPMFoam's gas feels -grad p and "
      "its particles the drag alone (\"model B\"); Wen-Yu's eps^-2.65 carries the "
      "buoyancy, so this is fluidbed's model A in a uniform bed; no pressureGradient "
      "force is added (it would count the pressure twice). In a uniform bed Wen-Yu / "
      "fluidbed's fluid force = " +
      g3(wen_yu_over_di_felice(s, eps, u_mf)) + " at eps = 0.42, U = 1.9 m/s; " +
      g3(wen_yu_over_di_felice(s, 0.8, 3.0)) + " at eps = 0.8, U = 3 m/s");
  n.push_back(
      "porosity: DPMFoam counts a sphere's whole volume in the cell holding its centre "
      "(fluidbed splits it exactly between the cells it straddles, eq 22)");
  n.push_back(
      "gas: DPMFoam's PIMPLE, Euler in time, laminar (fluidbed: SIMPLE, Crank-Nicolson, "
      "upwind; upwind here too)");
  if (m.thick)
    n.push_back(
        "front and back: walls for the spheres (the same spring-slider-dashpot as the side "
        "walls) and slip for the gas, one cell deep: the gas is 2-D with cells dx dy "
        "thickness (eq 23), as fluidbed's, while the spheres move through the slab's depth");
  else
    n.push_back(
        "front and back: \"empty\" patches, one cell deep: the gas is 2-D with cells dx dy "
        "thickness (eq 23) and DPMFoam keeps the spheres on the mid-plane, as fluidbed; "
        "slip walls instead would make the gas a 3-D layer and let spheres touch them");
  if (s.contact.rolling_friction > 0.0)
    n.push_back("rolling resistance: DPMFoam's collision models have none, so the scene's "
                "contact.rolling_friction = " +
                num(s.contact.rolling_friction) + " is left out");

  if (!m.uniform_cells)
    n.push_back(
        "the jet slot's edges are not on the scene's grid lines: the cells beside and "
        "in the slot are stretched to fit it");
  if (!s.domain.top_wall)
    n.push_back("a sphere reaching the open top leaves the case (fluidbed stops the run)");
  bool moving = false;
  for (std::size_t i = 0; i < p.size(); ++i)
    moving = moving || p.vx[i] != 0.0 || p.vy[i] != 0.0 || p.w[i] != 0.0 ||
             (m.thick && (p.vz[i] != 0.0 || p.wx[i] != 0.0 || p.wy[i] != 0.0));
  if (moving)
    n.push_back(
        "the start's velocities and spins are left out: DPMFoam's manual injection "
        "starts every sphere at rest");
  if (s.particles.placement == Placement::State || s.particles.placement == Placement::Packed)
    n.push_back(
        "the start's contact history is left out: springs start from zero and overlaps "
        "from the geometry");
  if (s.coupling.particle_steps_per_gas_step != 1)
    n.push_back("the gas is stepped with every particle step (the scene: every " +
                std::to_string(s.coupling.particle_steps_per_gas_step) + ")");
  return n;
}

}  // namespace

OpenfoamCase write_openfoam_case(const Settings& s, const std::string& dir,
                                 const std::function<void(const std::string&)>& notify) {
  if (!s.gas.enabled)
    throw InputError(
        "the scene has no [gas]: a DPMFoam case is a gas with particles (export "
        "it --to liggghts, or add a [gas] section)");
  if (s.particles.frozen)
    throw InputError("particles.frozen: DPMFoam's particles cannot be held in place");
  if (s.contact.wall_friction)
    throw InputError("contact.wall_friction: the DPMFoam case's walls take the particles' "
                     "friction, so walls with their own are not exported (leave it unset)");
  if (s.contact.law == ContactLaw::HertzMindlin)
    throw InputError("contact.law = \"hertz_mindlin\": the DPMFoam case is written for the "
                     "linear spring only (export a scene with contact.law = \"linear\")");
  if (s.inlet.plenum_height > 0.0)
    throw InputError("inlet.plenum_height: the DPMFoam case's mesh starts at the particles' "
                     "floor, so a plenum under it is not exported (set it to 0)");
  if (s.inlet.kind == InletKind::Jet && s.inlet.jets != 1)
    throw InputError("inlet.jets = " + std::to_string(s.inlet.jets) +
                     ": the DPMFoam case has one central jet slot (export a bed with jets = 1)");
  if (s.inlet.kind == InletKind::Jet && (s.gas.cells_x < 3 || s.inlet.jet_width >= s.domain.width))
    throw InputError(
        "inlet.jet_width / gas.cells_x: the jet slot needs a cell of its own and one "
        "on each side (cells_x >= 3, jet_width < width)");
  const Mesh m = mesh_for(s);
  const DpmCollisionLaw law = dpm_collision_law(s);
  const Particles p = start_particles(s, notify);
  const std::vector<std::string> notes = notes_for(s, law, m, p);

  // Every file rendered before the folder is touched, so that a refusal writes nothing.
  std::vector<std::pair<std::string, std::string>> files;  // path in the case, text
  auto add = [&files](const std::string& path, const std::function<void(std::ostream&)>& fill) {
    std::ostringstream o;
    fill(o);
    files.emplace_back(path, o.str());
  };
  add("system/blockMeshDict", [&](std::ostream& o) { write_block_mesh(o, s, m); });
  add("system/controlDict", [&](std::ostream& o) { write_control(o, s); });
  add("system/fvSchemes", [&](std::ostream& o) { write_schemes(o); });
  add("system/fvSolution", [&](std::ostream& o) { write_solution(o, s); });
  add("system/decomposeParDict", [&](std::ostream& o) { write_decompose(o); });
  add("constant/g", [&](std::ostream& o) { write_gravity(o, s); });
  add("constant/transportProperties", [&](std::ostream& o) { write_transport(o, s); });
  add("constant/turbulenceProperties.air", [&](std::ostream& o) { write_turbulence(o); });
  add("constant/kinematicCloudProperties", [&](std::ostream& o) { write_cloud(o, s, law, notes); });
  add("constant/kinematicCloudPositions", [&](std::ostream& o) { write_positions(o, s, m, p); });
  add("0/p", [&](std::ostream& o) { write_pressure(o, m); });
  add("0/U.air", [&](std::ostream& o) { write_velocity(o, s, m); });
  add("Allrun", [&](std::ostream& o) { write_allrun(o, s, notes); });

  namespace fs = std::filesystem;
  std::error_code ec;
  for (const char* sub : {"system", "constant", "0"}) {
    fs::create_directories(fs::path(dir) / sub, ec);
    if (ec)
      throw InputError("cannot create " + (fs::path(dir) / sub).string() + ": " + ec.message());
  }
  for (const auto& [path, text] : files)
    write_file_atomically((fs::path(dir) / path).string(),
                          [&text](std::ostream& out) { out << text; });
  OpenfoamCase c;
  c.dir = dir;
  c.allrun = (fs::path(dir) / "Allrun").string();
  fs::permissions(c.allrun, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add, ec);
  if (ec) throw InputError("cannot make " + c.allrun + " executable: " + ec.message());
  c.particles = p.size();
  c.notes = notes;
  return c;
}

}  // namespace fluidbed
