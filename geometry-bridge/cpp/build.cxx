// Construction: the project's own CAD samples, built through OCCT and written as STEP.
// A lofted wing (section wires of B-spline edges interpolating the given points) cut out of a
// far-field box, with XDE names on the solid and its faces so they become boundary markers.
#include "tetrafoil-occt/cpp/shim.hxx"
#include "tetrafoil-occt/src/ffi.rs.h"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPCAFControl_Controller.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Writer.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TDF_Label.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

#include <cmath>
#include <stdexcept>
#include <string>

namespace tfo {

namespace {

double volume(const TopoDS_Shape &s) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(s, props, 1e-9);
  return props.Mass();
}

// One closed section wire: a single non-periodic B-spline edge through the points, whose
// first and last points coincide (a sharp trailing edge stays sharp).
TopoDS_Wire section_wire(rust::Slice<const double> xyz, size_t first, size_t count) {
  if (count < 4) {
    throw std::invalid_argument("a section needs at least 4 points");
  }
  Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, static_cast<int>(count));
  for (size_t k = 0; k < count; ++k) {
    size_t at = 3 * (first + k);
    pts->SetValue(static_cast<int>(k + 1), gp_Pnt(xyz[at], xyz[at + 1], xyz[at + 2]));
  }
  if (!pts->Value(1).IsEqual(pts->Value(static_cast<int>(count)), 1e-12)) {
    throw std::invalid_argument("a section must end where it starts (closed trailing edge)");
  }
  GeomAPI_Interpolate interp(pts, false, 1e-9);
  interp.Perform();
  if (!interp.IsDone()) {
    throw std::runtime_error("B-spline interpolation of a section failed");
  }
  BRepBuilderAPI_MakeEdge edge(interp.Curve());
  if (!edge.IsDone()) {
    throw std::runtime_error("section edge construction failed");
  }
  BRepBuilderAPI_MakeWire wire(edge.Edge());
  if (!wire.IsDone()) {
    throw std::runtime_error("section wire construction failed");
  }
  return wire.Wire();
}

// Which boundary a face of the cut solid is: on the plane y = lo.y ("symmetry"), on another
// box plane ("farfield"), else the wing.
const char *classify(const TopoDS_Face &f, rust::Slice<const double> b) {
  Bnd_Box bb;
  BRepBndLib::AddOptimal(f, bb, false, false);
  double x0, y0, z0, x1, y1, z1;
  bb.Get(x0, y0, z0, x1, y1, z1);
  double lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
  double tol = 1e-7 * (1.0 + std::abs(b[3] - b[0]) + std::abs(b[4] - b[1]) +
                       std::abs(b[5] - b[2]));
  for (int k = 0; k < 3; ++k) {
    for (int side = 0; side < 2; ++side) {
      double plane = b[3 * side + k];
      if (std::abs(lo[k] - plane) <= tol && std::abs(hi[k] - plane) <= tol) {
        return (k == 1 && side == 0) ? "symmetry" : "farfield";
      }
    }
  }
  return "wing";
}

} // namespace

void wing_in_box(rust::Slice<const double> points, rust::Slice<const int32_t> counts,
                 rust::Slice<const double> bounds, rust::Str path, BuildStats &stats) {
  BRepOffsetAPI_ThruSections loft(true, false, 1e-6);
  loft.CheckCompatibility(false);
  size_t first = 0;
  for (int32_t n : counts) {
    loft.AddWire(section_wire(points, first, static_cast<size_t>(n)));
    first += static_cast<size_t>(n);
  }
  if (3 * first != points.size()) {
    throw std::invalid_argument("section point counts do not add up to the points given");
  }
  loft.Build();
  if (!loft.IsDone()) {
    throw std::runtime_error("loft (ThruSections) failed");
  }
  TopoDS_Shape wing = loft.Shape();
  stats.wing_volume = volume(wing);

  BRepPrimAPI_MakeBox box(gp_Pnt(bounds[0], bounds[1], bounds[2]),
                          gp_Pnt(bounds[3], bounds[4], bounds[5]));
  BRepAlgoAPI_Cut cut(box.Shape(), wing);
  if (!cut.IsDone() || cut.HasErrors()) {
    throw std::runtime_error("boolean cut of the wing from the box failed");
  }
  TopExp_Explorer solids(cut.Shape(), TopAbs_SOLID);
  if (!solids.More()) {
    throw std::runtime_error("the cut left no solid");
  }
  TopoDS_Solid fluid = TopoDS::Solid(solids.Current());
  solids.Next();
  if (solids.More()) {
    throw std::runtime_error("the cut left more than one solid");
  }
  if (!BRepCheck_Analyzer(fluid).IsValid()) {
    throw std::runtime_error("the cut solid is not valid (BRepCheck)");
  }
  stats.fluid_volume = volume(fluid);

  std::vector<std::string> names;
  for (TopExp_Explorer ex(fluid, TopAbs_FACE); ex.More(); ex.Next()) {
    std::string name = classify(TopoDS::Face(ex.Current()), bounds);
    stats.faces += 1;
    stats.wing_faces += name == "wing";
    stats.symmetry_faces += name == "symmetry";
    names.push_back(name);
  }
  write_named_solid(fluid, "fluid", names, path);
}

void write_named_solid(const TopoDS_Solid &solid, const char *solid_name,
                       const std::vector<std::string> &face_names, rust::Str path) {
  Handle(TDocStd_Document) doc = new TDocStd_Document("MDTV-XCAF");
  Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  TDF_Label label = tool->AddShape(solid, false);
  TDataStd_Name::Set(label, solid_name);
  size_t k = 0;
  for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next(), ++k) {
    if (k >= face_names.size()) {
      throw std::invalid_argument("fewer face names than faces");
    }
    TDF_Label sub = tool->AddSubShape(label, ex.Current());
    if (!sub.IsNull()) {
      TDataStd_Name::Set(sub, TCollection_ExtendedString(face_names[k].c_str()));
    }
  }

  STEPCAFControl_Controller::Init();
  Interface_Static::SetIVal("write.stepcaf.subshapes.name", 1);
  STEPCAFControl_Writer writer;
  writer.SetNameMode(true);
  writer.SetColorMode(false);
  writer.SetLayerMode(false);
  if (!writer.Transfer(doc, STEPControl_AsIs)) {
    throw std::runtime_error("STEP transfer failed");
  }
  // A fixed header, so regenerating the sample gives the same bytes.
  APIHeaderSection_MakeHeader header(writer.ChangeWriter().Model());
  header.SetTimeStamp(new TCollection_HAsciiString("2024-01-01T00:00:00"));
  header.SetOriginatingSystem(new TCollection_HAsciiString("tetrafoil (OpenCASCADE)"));
  header.SetAuthorValue(1, new TCollection_HAsciiString("tetrafoil"));
  std::string file(path);
  if (writer.Write(file.c_str()) != IFSelect_RetDone) {
    throw std::runtime_error("writing " + file + " failed");
  }
}

void loose_polygons(rust::Slice<const double> points, rust::Slice<const int32_t> counts,
                    rust::Str path) {
  // Each polygon becomes a planar face of its own edges: neighbouring faces share no edge, as
  // in a surface set exported without topology, and sewing must find which edges meet.
  BRep_Builder builder;
  TopoDS_Compound faces;
  builder.MakeCompound(faces);
  size_t first = 0;
  for (int32_t n : counts) {
    BRepBuilderAPI_MakePolygon polygon;
    for (size_t i = first; i < first + static_cast<size_t>(n); ++i) {
      polygon.Add(gp_Pnt(points[3 * i], points[3 * i + 1], points[3 * i + 2]));
    }
    polygon.Close();
    BRepBuilderAPI_MakeFace face(polygon.Wire(), true);
    if (!face.IsDone()) {
      throw std::runtime_error("polygon from point " + std::to_string(first) +
                               " is not a planar face");
    }
    builder.Add(faces, face.Face());
    first += static_cast<size_t>(n);
  }
  STEPControl_Writer writer;
  if (writer.Transfer(faces, STEPControl_AsIs) != IFSelect_RetDone) {
    throw std::runtime_error("STEP transfer failed");
  }
  std::string file(path);
  if (writer.Write(file.c_str()) != IFSelect_RetDone) {
    throw std::runtime_error("writing " + file + " failed");
  }
}

} // namespace tfo
