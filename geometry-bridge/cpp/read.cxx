// Reading STEP through XDE (so face and solid names survive) and numbering sub-shapes.
#include "tetrafoil-occt/cpp/shim.hxx"
#include "tetrafoil-occt/src/ffi.rs.h"

#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPCAFControl_Controller.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS_Compound.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

#include <mutex>

namespace tfo {

ShapeIndex::ShapeIndex(const TopoDS_Shape &s) : shape(s) {
  TopExp::MapShapes(s, TopAbs_VERTEX, vertices);
  TopExp::MapShapes(s, TopAbs_EDGE, edges);
  TopExp::MapShapes(s, TopAbs_FACE, faces);
  TopExp::MapShapes(s, TopAbs_SHELL, shells);
  TopExp::MapShapes(s, TopAbs_SOLID, solids);
}

std::unique_ptr<ShapeIndex> index_shape(const TopoDS_Shape &shape) {
  return std::make_unique<ShapeIndex>(shape);
}

std::unique_ptr<TopoDS_Shape> sub_shape(const ShapeIndex &idx, int32_t kind, int32_t i) {
  const TopTools_IndexedMapOfShape *m = nullptr;
  switch (kind) {
  case 0: m = &idx.vertices; break;
  case 1: m = &idx.edges; break;
  case 2: m = &idx.faces; break;
  case 3: m = &idx.shells; break;
  case 4: m = &idx.solids; break;
  default: return std::make_unique<TopoDS_Shape>(idx.shape);
  }
  if (i < 0 || i >= m->Extent()) {
    throw std::out_of_range("sub-shape index out of range");
  }
  return std::make_unique<TopoDS_Shape>(m->FindKey(i + 1));
}

namespace {

bool label_name(const TDF_Label &label, TCollection_AsciiString &name) {
  Handle(TDataStd_Name) attr;
  if (!label.FindAttribute(TDataStd_Name::GetID(), attr)) {
    return false;
  }
  name = TCollection_AsciiString(attr->Get());
  return !name.IsEmpty();
}

// Records names of a label's shape and its named sub-shapes, moved by the instance location
// `loc` so keys match sub-shapes as TopExp finds them in the assembled root shape.
void collect_names(const TDF_Label &label, const TopLoc_Location &loc, NameMap &names) {
  if (XCAFDoc_ShapeTool::IsAssembly(label)) {
    TDF_LabelSequence comps;
    XCAFDoc_ShapeTool::GetComponents(label, comps);
    for (Standard_Integer i = 1; i <= comps.Length(); ++i) {
      TDF_Label ref;
      if (!XCAFDoc_ShapeTool::GetReferredShape(comps.Value(i), ref)) {
        continue;
      }
      TopLoc_Location sub = loc * XCAFDoc_ShapeTool::GetLocation(comps.Value(i));
      TCollection_AsciiString name;
      // An instance name names the located solid(s) better than the product name does.
      if (label_name(comps.Value(i), name)) {
        TopoDS_Shape s = XCAFDoc_ShapeTool::GetShape(ref);
        if (!s.IsNull()) {
          names.Bind(s.Moved(sub), name);
        }
      }
      collect_names(ref, sub, names);
    }
    return;
  }
  TopoDS_Shape s = XCAFDoc_ShapeTool::GetShape(label);
  TCollection_AsciiString name;
  if (!s.IsNull() && label_name(label, name) && !names.IsBound(s.Moved(loc))) {
    names.Bind(s.Moved(loc), name);
  }
  TDF_LabelSequence subs;
  XCAFDoc_ShapeTool::GetSubShapes(label, subs);
  for (Standard_Integer i = 1; i <= subs.Length(); ++i) {
    TopoDS_Shape ss = XCAFDoc_ShapeTool::GetShape(subs.Value(i));
    if (!ss.IsNull() && label_name(subs.Value(i), name)) {
      names.Bind(ss.Moved(loc), name);
    }
  }
}

// Interface_Static parameters are process-global; readers are configured one at a time.
std::mutex &static_params_lock() {
  static std::mutex m;
  return m;
}

} // namespace

void quiet_messages() {
  // A library must not write to the program's stdout; keep only failures, on stderr.
  static std::once_flag once;
  std::call_once(once, [] {
    const Handle(Message_Messenger) &m = Message::DefaultMessenger();
    m->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    m->AddPrinter(new Message_PrinterOStream("cerr", false, Message_Fail));
  });
}

std::unique_ptr<ShapeIndex> read_step_xde(rust::Str path, int32_t &status) {
  std::string file(path);
  Handle(TDocStd_Document) doc = new TDocStd_Document("MDTV-XCAF");
  STEPCAFControl_Reader reader;
  {
    std::lock_guard<std::mutex> guard(static_params_lock());
    STEPCAFControl_Controller::Init();
    Interface_Static::SetIVal("read.stepcaf.subshapes.name", 1);
    reader.SetNameMode(true);
    reader.SetColorMode(false);
    reader.SetLayerMode(false);
    if (reader.ReadFile(file.c_str()) != IFSelect_RetDone) {
      status = 1;
      return nullptr;
    }
  }
  if (!reader.Transfer(doc)) {
    status = 2;
    return nullptr;
  }
  Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  TDF_LabelSequence roots;
  tool->GetFreeShapes(roots);
  BRep_Builder builder;
  TopoDS_Compound all;
  builder.MakeCompound(all);
  NameMap names;
  int count = 0;
  TopoDS_Shape single;
  for (Standard_Integer i = 1; i <= roots.Length(); ++i) {
    TopoDS_Shape s = XCAFDoc_ShapeTool::GetShape(roots.Value(i));
    if (s.IsNull()) {
      continue;
    }
    builder.Add(all, s);
    single = s;
    ++count;
    collect_names(roots.Value(i), TopLoc_Location(), names);
  }
  if (count == 0) {
    status = 2;
    return nullptr;
  }
  auto idx = std::make_unique<ShapeIndex>(count == 1 ? single : TopoDS_Shape(all));
  if (idx->faces.Extent() == 0 && idx->edges.Extent() == 0) {
    status = 2;
    return nullptr;
  }
  idx->names = names;
  status = 0;
  return idx;
}

} // namespace tfo
