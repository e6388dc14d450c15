// Construction: a body fused from lofted parts (the jet sample: fuselage, wing, tails,
// nacelle, pylon), cut to its y >= 0 half when asked, written as STEP with XDE names: each
// face named after the part it came from (carried through the booleans' history), the faces
// the half cut made named "symmetry"; written by build.cxx's write_named_solid.
#include "tetrafoil-occt/cpp/shim.hxx"
#include "tetrafoil-occt/src/ffi.rs.h"

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeInteger.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace tfo {

namespace {

double solid_volume(const TopoDS_Shape &s) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(s, props, 1e-9);
  return props.Mass();
}

// One closed section: `count` points from `first`. Periodic: a periodic B-spline through the
// points (a smooth ring: fuselage, nacelle); otherwise the last point repeats the first and
// one B-spline runs through them (an aerofoil, sharp at its trailing edge).
TopoDS_Wire section(rust::Slice<const double> xyz, size_t first, size_t count, bool periodic) {
  size_t n = count;
  if (n < 4) {
    throw std::invalid_argument("a section needs at least 4 points");
  }
  Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, static_cast<int>(n));
  for (size_t k = 0; k < n; ++k) {
    size_t at = 3 * (first + k);
    pts->SetValue(static_cast<int>(k + 1), gp_Pnt(xyz[at], xyz[at + 1], xyz[at + 2]));
  }
  bool closed = pts->Value(1).IsEqual(pts->Value(static_cast<int>(n)), 1e-12);
  if (periodic == closed) {
    throw std::invalid_argument(periodic
                                    ? "a ring section must not repeat its first point"
                                    : "an aerofoil section must end where it starts");
  }
  GeomAPI_Interpolate interp(pts, periodic, 1e-9);
  interp.Perform();
  if (!interp.IsDone()) {
    throw std::runtime_error("B-spline interpolation of a section failed");
  }
  BRepBuilderAPI_MakeEdge edge(interp.Curve());
  BRepBuilderAPI_MakeWire wire(edge.Edge());
  if (!wire.IsDone()) {
    throw std::runtime_error("section wire construction failed");
  }
  return wire.Wire();
}

// Names carried through one boolean: each named face to the faces it became.
void carry(BRepAlgoAPI_BooleanOperation &op, TopTools_DataMapOfShapeInteger &names) {
  TopTools_DataMapOfShapeInteger next;
  for (TopTools_DataMapIteratorOfDataMapOfShapeInteger it(names); it.More(); it.Next()) {
    const TopTools_ListOfShape &modified = op.Modified(it.Key());
    if (!modified.IsEmpty()) {
      for (TopTools_ListIteratorOfListOfShape m(modified); m.More(); m.Next()) {
        next.Bind(m.Value(), it.Value());
      }
    } else if (!op.IsDeleted(it.Key())) {
      next.Bind(it.Key(), it.Value());
    }
  }
  names = next;
}

void check(const BRepAlgoAPI_BooleanOperation &op, const std::string &what) {
  if (!op.IsDone() || op.HasErrors()) {
    throw std::runtime_error(what + " failed");
  }
}

TopoDS_Solid only_solid(const TopoDS_Shape &s, const std::string &what) {
  TopExp_Explorer solids(s, TopAbs_SOLID);
  if (!solids.More()) {
    throw std::runtime_error(what + " left no solid");
  }
  TopoDS_Solid solid = TopoDS::Solid(solids.Current());
  solids.Next();
  if (solids.More()) {
    throw std::runtime_error(what + " left more than one solid");
  }
  return solid;
}

} // namespace

void lofted_body(rust::Slice<const double> points, rust::Slice<const int32_t> counts,
                 rust::Slice<const int32_t> sections_per_part,
                 rust::Slice<const int32_t> part_flags, rust::Slice<const double> tips,
                 rust::Str names, bool half, rust::Str path, BodyStats &stats) {
  std::vector<std::string> part_names;
  {
    std::istringstream lines{std::string(names)};
    for (std::string line; std::getline(lines, line);) {
      part_names.push_back(line);
    }
  }
  size_t parts = sections_per_part.size();
  if (part_flags.size() != parts || tips.size() != 6 * parts || part_names.size() != parts) {
    throw std::invalid_argument("per-part flags, tips and names do not match the parts");
  }
  std::vector<TopoDS_Shape> solids;
  TopTools_DataMapOfShapeInteger named;
  size_t section_at = 0, point_at = 0;
  for (size_t p = 0; p < parts; ++p) {
    int32_t flags = part_flags[p];
    BRepOffsetAPI_ThruSections loft(true, false, 1e-6);
    loft.CheckCompatibility(false);
    if (flags & 2) {
      loft.AddVertex(BRepBuilderAPI_MakeVertex(gp_Pnt(tips[6 * p], tips[6 * p + 1],
                                                      tips[6 * p + 2])));
    }
    for (int32_t s = 0; s < sections_per_part[p]; ++s) {
      if (section_at >= counts.size()) {
        throw std::invalid_argument("more sections asked for than given");
      }
      size_t n = static_cast<size_t>(counts[section_at++]);
      loft.AddWire(section(points, point_at, n, flags & 1));
      point_at += n;
    }
    if (flags & 4) {
      loft.AddVertex(BRepBuilderAPI_MakeVertex(gp_Pnt(tips[6 * p + 3], tips[6 * p + 4],
                                                      tips[6 * p + 5])));
    }
    loft.Build();
    if (!loft.IsDone()) {
      throw std::runtime_error("loft of part '" + part_names[p] + "' failed");
    }
    TopoDS_Shape solid = loft.Shape();
    stats.parts_volume += solid_volume(solid);
    for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
      named.Bind(ex.Current(), static_cast<int>(p));
    }
    solids.push_back(solid);
  }
  if (3 * point_at != points.size() || section_at != counts.size()) {
    throw std::invalid_argument("section counts do not add up to the points given");
  }
  if (solids.empty()) {
    throw std::invalid_argument("no parts");
  }

  TopoDS_Shape body = solids[0];
  if (solids.size() > 1) {
    BRepAlgoAPI_Fuse fuse;
    TopTools_ListOfShape arguments, tools;
    arguments.Append(solids[0]);
    for (size_t p = 1; p < solids.size(); ++p) {
      tools.Append(solids[p]);
    }
    fuse.SetArguments(arguments);
    fuse.SetTools(tools);
    fuse.Build();
    check(fuse, "fusing the parts");
    carry(fuse, named);
    body = only_solid(fuse.Shape(), "fusing the parts");
  }
  if (half) {
    Bnd_Box bb;
    BRepBndLib::Add(body, bb);
    double x0, y0, z0, x1, y1, z1;
    bb.Get(x0, y0, z0, x1, y1, z1);
    double pad = 1.0 + (x1 - x0) + (y1 - y0) + (z1 - z0);
    BRepPrimAPI_MakeBox minus_y(gp_Pnt(x0 - pad, y0 - pad, z0 - pad), gp_Pnt(x1 + pad, 0.0, z1 + pad));
    BRepAlgoAPI_Cut cut(body, minus_y.Shape());
    check(cut, "cutting the body at y = 0");
    carry(cut, named);
    body = only_solid(cut.Shape(), "cutting the body at y = 0");
  }
  TopoDS_Solid solid = TopoDS::Solid(body);
  if (!BRepCheck_Analyzer(solid).IsValid()) {
    throw std::runtime_error("the body is not a valid solid (BRepCheck)");
  }
  stats.volume = solid_volume(solid);

  std::vector<std::string> face_names;
  for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Shape &f = ex.Current();
    std::string name = named.IsBound(f) ? part_names[named.Find(f)] : "symmetry";
    stats.faces += 1;
    stats.symmetry_faces += name == "symmetry";
    face_names.push_back(name);
  }
  write_named_solid(solid, "body", face_names, path);
}

} // namespace tfo
