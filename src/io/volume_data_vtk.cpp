// VTK datasets and NIfTI images as volume data (io/volume_data.h): the points of any dataset
// (image data: voxel centres, origin and spacing respected) and its point data arrays, one
// attribute per component. Errors VTK reports arrive as ErrorEvents, collected by an observer
// instead of being printed.
#include "volume_data_vtk.h"

#include <cctype>
#include <cmath>
#include <fstream>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDataSetReader.h>
#include <vtkPolyDataReader.h>
#include <vtkRectilinearGridReader.h>
#include <vtkStructuredGridReader.h>
#include <vtkStructuredPointsReader.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "../mesh/vtk_reader_errors.h"
#include "volspline/core/error.h"

namespace volspline::detail {
namespace {

VolumeData from_dataset(vtkDataSet* set, const std::string& source, const vtkMatrix4x4* to_world) {
  VolumeData data;
  const vtkIdType n = set->GetNumberOfPoints();
  if (n == 0) throw InvalidInput("the dataset has no points", source);
  data.points.reserve(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    set->GetPoint(i, p);
    if (to_world) {
      double h[4] = {p[0], p[1], p[2], 1}, w[4];
      const_cast<vtkMatrix4x4*>(to_world)->MultiplyPoint(h, w);
      p[0] = w[0], p[1] = w[1], p[2] = w[2];
    }
    data.points.emplace_back(p[0], p[1], p[2]);
  }
  vtkPointData* point_data = set->GetPointData();
  std::vector<vtkDataArray*> arrays;
  for (int a = 0; point_data && a < point_data->GetNumberOfArrays(); ++a)
    if (vtkDataArray* array = point_data->GetArray(a)) arrays.push_back(array);
  int columns = 0;
  for (vtkDataArray* array : arrays) columns += array->GetNumberOfComponents();
  data.attributes.resize(static_cast<Eigen::Index>(n), columns);
  int column = 0;
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    vtkDataArray* array = arrays[a];
    const std::string name = array->GetName() && *array->GetName() ? array->GetName() : "array_" + std::to_string(a);
    if (array->GetNumberOfTuples() != n)
      throw InvalidInput("point data array '" + name + "' has " + std::to_string(array->GetNumberOfTuples()) + " values, expected " +
                             std::to_string(n) + " (one per point)",
                         source);
    const int components = array->GetNumberOfComponents();
    for (int c = 0; c < components; ++c, ++column) {
      data.attribute_names.push_back(components == 1 ? name : name + "_" + std::to_string(c));
      for (vtkIdType i = 0; i < n; ++i) data.attributes(static_cast<Eigen::Index>(i), column) = array->GetComponent(i, c);
    }
  }
  return data;
}

template <class Reader>
VolumeData read_with(const std::filesystem::path& path, const char* expected) {
  const std::string source = path.string();
  VtkErrors errors;
  vtkNew<Reader> reader;
  errors.watch(*reader);
  if (!reader->CanReadFile(source.c_str())) throw InvalidInput(std::string("not ") + expected, source);
  reader->SetFileName(source.c_str());
  reader->Update();
  if (!errors.first.empty()) throw InvalidInput(vtk_message_text(errors.first), source);
  vtkDataSet* set = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
  if (!set) throw InvalidInput(std::string("the VTK reader produced no dataset (expected ") + expected + ")", source);
  const vtkMatrix4x4* to_world = nullptr;
  if constexpr (std::is_same_v<Reader, vtkNIFTIImageReader>) {
    // NIfTI's voxel-to-world map: the sform where the file sets one, else the qform; VTK gives
    // the voxel centres as (i, j, k) * spacing and leaves the matrix to the caller.
    to_world = reader->GetSFormMatrix() ? reader->GetSFormMatrix() : reader->GetQFormMatrix();
  }
  VolumeData data = from_dataset(set, source, to_world);
  if constexpr (std::is_same_v<Reader, vtkNIFTIImageReader>) {
    // The stored values are scl_slope * raw + scl_inter (NIfTI-1; a slope of 0 means none): CT
    // images store Hounsfield units so. VTK reads the raw values and reports the two.
    const double slope = reader->GetRescaleSlope(), intercept = reader->GetRescaleIntercept();
    if (std::isfinite(slope) && std::isfinite(intercept) && slope != 0 && (slope != 1 || intercept != 0))
      data.attributes = (slope * data.attributes.array() + intercept).matrix();
  }
  return data;
}

// A legacy file is read by the reader of its DATASET type itself: vtkDataSetReader delegates to
// one it makes inside, whose errors and warnings no observer of ours would see (a value that is
// not a number, or fewer values than declared, were read as zeros: an audit found both).
template <class Reader>
VolumeData read_legacy_as(const std::string& source) {
  VtkErrors errors;
  errors.warnings_are_errors = true;
  vtkNew<Reader> reader;
  errors.watch(*reader);
  reader->SetFileName(source.c_str());
  reader->ReadAllScalarsOn();
  reader->ReadAllVectorsOn();
  reader->ReadAllTensorsOff();
  {
    const CapturedOutput output;
    reader->Update();
    if (errors.first.empty() && !output.first().empty()) {
      errors.first = output.first();
      if (errors.first.find("mismatch of datasize") != std::string::npos)
        errors.first += " (expected as many numbers as the header declares: the file holds fewer, or one that is not a number)";
    }
  }
  if (!errors.first.empty()) throw InvalidInput(vtk_message_text(errors.first), source);
  vtkDataSet* set = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
  if (!set) throw InvalidInput("the VTK reader produced no dataset (expected a legacy VTK dataset)", source);
  return from_dataset(set, source, nullptr);
}

VolumeData read_legacy(const std::filesystem::path& path) {
  const std::string source = path.string();
  VtkErrors errors;
  vtkNew<vtkDataSetReader> probe;
  errors.watch(*probe);
  probe->SetFileName(source.c_str());
  switch (probe->ReadOutputType()) {
    case VTK_POLY_DATA: return read_legacy_as<vtkPolyDataReader>(source);
    case VTK_UNSTRUCTURED_GRID: return read_legacy_as<vtkUnstructuredGridReader>(source);
    case VTK_STRUCTURED_POINTS:
    case VTK_IMAGE_DATA: return read_legacy_as<vtkStructuredPointsReader>(source);
    case VTK_STRUCTURED_GRID: return read_legacy_as<vtkStructuredGridReader>(source);
    case VTK_RECTILINEAR_GRID: return read_legacy_as<vtkRectilinearGridReader>(source);
    default: break;
  }
  throw InvalidInput(errors.first.empty() ? std::string("not a legacy VTK dataset (expected a DATASET line naming POLYDATA, "
                                                        "UNSTRUCTURED_GRID, STRUCTURED_POINTS, STRUCTURED_GRID or RECTILINEAR_GRID)")
                                          : vtk_message_text(errors.first),
                     source);
}

}  // namespace

VolumeData read_vtk_volume_data(const std::filesystem::path& path, const std::string& extension) {
  if (!std::ifstream(path, std::ios::binary)) throw IoError("cannot open " + path.string());
  if (extension == ".vtu") return read_with<vtkXMLUnstructuredGridReader>(path, "a VTK XML unstructured grid (VTKFile type=\"UnstructuredGrid\")");
  if (extension == ".vti") return read_with<vtkXMLImageDataReader>(path, "a VTK XML image (VTKFile type=\"ImageData\")");
  if (extension == ".nii") return read_with<vtkNIFTIImageReader>(path, "a NIfTI-1 image (.nii or .nii.gz)");
  return read_legacy(path);
}

}  // namespace volspline::detail
