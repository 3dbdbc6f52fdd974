#include "core/hdf5.h"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/error.h"
#include "core/format.h"

namespace spallkit::h5 {
namespace {

static_assert(sizeof(hid_t) == sizeof(long long) && std::is_signed_v<hid_t>,
              "hid_t must fit the long long kept in hdf5.h");

// HDF5 prints its error stack to stderr by default; library code must not print. The silencer
// turns automatic printing off for the duration of one wrapper call and restores it afterwards,
// so callers that rely on HDF5's own reporting elsewhere are not affected.
class ErrorSilencer {
 public:
  ErrorSilencer() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~ErrorSilencer() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  ErrorSilencer(const ErrorSilencer&) = delete;
  ErrorSilencer& operator=(const ErrorSilencer&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// Owns one hid_t and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

std::string Normalize(const std::string& path) {
  if (path.empty()) return "/";
  return path.front() == '/' ? path : "/" + path;
}

[[noreturn]] void Fail(const std::string& file, const std::string& what) {
  throw InputError(file + ": " + what);
}

// A link-creation property list that creates missing intermediate groups.
Handle IntermediateGroupsLcpl() {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  return lcpl;
}

bool ExistsIn(hid_t file, const std::string& raw_path) {
  const std::string path = Normalize(raw_path);
  if (path == "/") return true;
  // H5Lexists fails (rather than returning false) when an intermediate link is missing, so test
  // each level in turn.
  size_t pos = 0;
  while (pos != std::string::npos) {
    pos = path.find('/', pos + 1);
    const std::string prefix = path.substr(0, pos);
    if (prefix.size() <= 1) continue;
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (pos != std::string::npos) {
      // The intermediate object must be a group for the next level to be meaningful.
      H5O_info_t info;
      if (H5Oget_info_by_name(file, prefix.c_str(), &info, H5P_DEFAULT) < 0 ||
          info.type != H5O_TYPE_GROUP) {
        return false;
      }
    }
  }
  return true;
}

void WriteFloat64(hid_t file,
                  const std::string& file_name,
                  const std::string& raw_path,
                  const double* data,
                  const hsize_t* dims,
                  int rank) {
  const std::string path = Normalize(raw_path);
  if (path == "/") Fail(file_name, "cannot write a dataset at the root path '/'");
  if (ExistsIn(file, path) && H5Ldelete(file, path.c_str(), H5P_DEFAULT) < 0) {
    Fail(file_name, path + ": cannot replace the existing object");
  }
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  Handle lcpl = IntermediateGroupsLcpl();
  Handle dset(
      H5Dcreate2(
          file, path.c_str(), H5T_IEEE_F64LE, space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (!dset.ok()) Fail(file_name, path + ": cannot create dataset (is a parent a dataset?)");
  hsize_t total = 1;
  for (int i = 0; i < rank; ++i) total *= dims[i];
  if (total > 0 &&
      H5Dwrite(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    Fail(file_name, path + ": write failed");
  }
}

Handle OpenObject(hid_t file, const std::string& file_name, const std::string& raw_path) {
  const std::string path = Normalize(raw_path);
  if (!ExistsIn(file, path)) Fail(file_name, path + ": no such group or dataset");
  Handle obj(H5Oopen(file, path.c_str(), H5P_DEFAULT), H5Oclose);
  if (!obj.ok()) Fail(file_name, path + ": cannot open");
  return obj;
}

Handle OpenDataset(hid_t file, const std::string& file_name, const std::string& raw_path) {
  const std::string path = Normalize(raw_path);
  if (!ExistsIn(file, path)) Fail(file_name, "dataset " + path + " not found");
  Handle dset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) Fail(file_name, path + ": not a dataset");
  return dset;
}

std::vector<size_t> DimsOf(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(std::max(rank, 0));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return std::vector<size_t>(dims.begin(), dims.end());
}

// Opens attribute `name` on the object; an invalid handle when the object has no such attribute.
Handle OpenAttribute(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) <= 0) return Handle(-1, H5Aclose);
  return Handle(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose);
}

// Attribute `name` of the object at `object_path`, opened for reading with its type and
// dataspace; nullopt when the object has no such attribute (a missing object is an InputError).
struct ReadableAttribute {
  Handle obj, attr, type, space;
};
std::optional<ReadableAttribute> OpenReadableAttribute(hid_t file,
                                                       const std::string& file_name,
                                                       const std::string& object_path,
                                                       const std::string& name) {
  Handle obj = OpenObject(file, file_name, object_path);
  Handle attr = OpenAttribute(obj.get(), name);
  if (!attr.ok()) return std::nullopt;
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  return ReadableAttribute{std::move(obj), std::move(attr), std::move(type), std::move(space)};
}

void ReplaceAttribute(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
}

}  // namespace

// HDF5 closes what is still open from an exit handler. A file whose close failed (a full disk)
// stays half-closed in its tables, and that handler then crashes or reports an endless loop on
// stderr after the one-line error: the process closes its files itself, so the handler is not
// installed (H5dont_atexit must come before any other HDF5 call of the process).
static void SkipExitCleanup() {
  static const bool once = [] {
    H5dont_atexit();
    return true;
  }();
  (void)once;
}

File File::Create(const std::string& path) {
  SkipExitCleanup();
  ErrorSilencer silence;
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) Fail(path, "cannot create HDF5 file (does the folder exist and is it writable?)");
  return File(id, path);
}

File File::OpenReadOnly(const std::string& path) {
  SkipExitCleanup();
  ErrorSilencer silence;
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  if (is_hdf5 < 0) Fail(path, "cannot open (no such file or not readable)");
  if (is_hdf5 == 0) Fail(path, "not an HDF5 file");
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) Fail(path, "cannot open HDF5 file");
  return File(id, path);
}

File::File(File&& other) noexcept : id_(other.id_), path_(std::move(other.path_)) {
  other.id_ = -1;
}

File& File::operator=(File&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0) {
      ErrorSilencer silence;
      H5Fclose(id_);
    }
    id_ = other.id_;
    path_ = std::move(other.path_);
    other.id_ = -1;
  }
  return *this;
}

File::~File() {
  if (id_ >= 0) {
    ErrorSilencer silence;
    H5Fclose(id_);
  }
}

void File::Close() {
  RequireOpen();
  ErrorSilencer silence;
  const hid_t id = id_;
  id_ = -1;
  if (H5Fflush(id, H5F_SCOPE_LOCAL) < 0) {
    H5Fclose(id);
    Fail(path_, "flush failed while closing (disk full?)");
  }
  if (H5Fclose(id) < 0) Fail(path_, "close failed");
}

void File::RequireOpen() const {
  if (id_ < 0) throw InputError(path_ + ": HDF5 file used after Close()");
}

void File::WriteDataset(const std::string& path, std::span<const double> data) {
  RequireOpen();
  ErrorSilencer silence;
  const hsize_t dims[1] = {static_cast<hsize_t>(data.size())};
  WriteFloat64(id_, path_, path, data.data(), dims, 1);
}

void File::WriteDataset2D(const std::string& path,
                          std::span<const double> row_major,
                          size_t rows,
                          size_t cols) {
  RequireOpen();
  if (row_major.size() != rows * cols) {
    Fail(path_,
         Normalize(path) + ": 2-D dataset needs rows*cols = " + std::to_string(rows * cols) +
             " values, got " + std::to_string(row_major.size()));
  }
  ErrorSilencer silence;
  const hsize_t dims[2] = {static_cast<hsize_t>(rows), static_cast<hsize_t>(cols)};
  WriteFloat64(id_, path_, path, row_major.data(), dims, 2);
}

void File::CreateGroup(const std::string& raw_path) {
  RequireOpen();
  ErrorSilencer silence;
  const std::string path = Normalize(raw_path);
  if (ExistsIn(id_, path)) {
    if (!IsDataset(path)) return;
    Fail(path_, path + ": exists and is a dataset, not a group");
  }
  Handle lcpl = IntermediateGroupsLcpl();
  Handle group(H5Gcreate2(id_, path.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!group.ok()) Fail(path_, path + ": cannot create group");
}

void File::SetAttribute(const std::string& object_path, const std::string& name, double value) {
  RequireOpen();
  ErrorSilencer silence;
  Handle obj = OpenObject(id_, path_, object_path);
  ReplaceAttribute(obj.get(), name);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(
      H5Acreate2(obj.get(), name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  if (!attr.ok() || H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value) < 0) {
    Fail(path_, Normalize(object_path) + ": cannot write attribute '" + name + "'");
  }
}

void File::SetAttribute(const std::string& object_path,
                        const std::string& name,
                        const std::string& value) {
  RequireOpen();
  ErrorSilencer silence;
  Handle obj = OpenObject(id_, path_, object_path);
  ReplaceAttribute(obj.get(), name);
  // Variable-length UTF-8: h5py returns str, MATLAB h5readatt returns char.
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(
      H5Acreate2(obj.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  const char* c_str = value.c_str();
  if (!attr.ok() || H5Awrite(attr.get(), type.get(), &c_str) < 0) {
    Fail(path_, Normalize(object_path) + ": cannot write attribute '" + name + "'");
  }
}

bool File::Exists(const std::string& path) const {
  RequireOpen();
  ErrorSilencer silence;
  return ExistsIn(id_, path);
}

bool File::IsDataset(const std::string& raw_path) const {
  RequireOpen();
  ErrorSilencer silence;
  const std::string path = Normalize(raw_path);
  if (!ExistsIn(id_, path)) return false;
  H5O_info_t info;
  if (H5Oget_info_by_name(id_, path.c_str(), &info, H5P_DEFAULT) < 0) return false;
  return info.type == H5O_TYPE_DATASET;
}

std::vector<size_t> File::DatasetDims(const std::string& path) const {
  RequireOpen();
  ErrorSilencer silence;
  Handle dset = OpenDataset(id_, path_, path);
  Handle space(H5Dget_space(dset.get()), H5Sclose);
  return DimsOf(space.get());
}

std::vector<double> File::ReadDataset(const std::string& raw_path,
                                      std::vector<size_t>* dims) const {
  RequireOpen();
  ErrorSilencer silence;
  const std::string path = Normalize(raw_path);
  Handle dset = OpenDataset(id_, path_, path);
  Handle type(H5Dget_type(dset.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) {
    Fail(path_, path + ": expected a numeric dataset");
  }
  Handle space(H5Dget_space(dset.get()), H5Sclose);
  std::vector<size_t> shape = DimsOf(space.get());
  // The declared size is the file's word: bound it before allocating (a dataset may declare
  // more elements than were written, or than memory holds). 2^32 doubles = 32 GiB.
  constexpr double kMaxElements = 4294967296.0;
  double declared = 1.0;
  for (size_t d : shape) declared *= static_cast<double>(d);
  if (declared > kMaxElements)
    Fail(path_,
         path + ": declares " + FormatNumber("%.3g", declared) +
             " values, more than the 2^32 a dataset may hold here");
  size_t total = 1;
  for (size_t d : shape) total *= d;
  std::vector<double> data(total);
  if (total > 0 &&
      H5Dread(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0) {
    Fail(path_, path + ": read failed");
  }
  if (dims) *dims = std::move(shape);
  return data;
}

std::optional<double> File::ReadDoubleAttribute(const std::string& object_path,
                                                const std::string& name) const {
  RequireOpen();
  ErrorSilencer silence;
  const std::optional<ReadableAttribute> a = OpenReadableAttribute(id_, path_, object_path, name);
  if (!a) return std::nullopt;
  const H5T_class_t cls = H5Tget_class(a->type.get());
  const hssize_t count = H5Sget_simple_extent_npoints(a->space.get());
  if ((cls != H5T_FLOAT && cls != H5T_INTEGER) || count != 1) {
    Fail(path_, Normalize(object_path) + ": attribute '" + name + "' is not a single number");
  }
  double value = 0;
  if (H5Aread(a->attr.get(), H5T_NATIVE_DOUBLE, &value) < 0) {
    Fail(path_, Normalize(object_path) + ": cannot read attribute '" + name + "'");
  }
  return value;
}

std::optional<std::string> File::ReadStringAttribute(const std::string& object_path,
                                                     const std::string& name) const {
  RequireOpen();
  ErrorSilencer silence;
  const std::optional<ReadableAttribute> a = OpenReadableAttribute(id_, path_, object_path, name);
  if (!a) return std::nullopt;
  const Handle& attr = a->attr;
  const Handle& type = a->type;
  const Handle& space = a->space;
  const std::string where = Normalize(object_path) + ": attribute '" + name + "'";
  if (H5Tget_class(type.get()) != H5T_STRING || H5Sget_simple_extent_npoints(space.get()) != 1) {
    Fail(path_, where + " is not a single string");
  }
  if (H5Tis_variable_str(type.get()) > 0) {
    Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mem.get(), H5T_VARIABLE);
    H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
    char* text = nullptr;
    if (H5Aread(attr.get(), mem.get(), &text) < 0) Fail(path_, where + ": read failed");
    std::string value = text ? text : "";
    H5free_memory(text);
    return value;
  }
  const size_t size = H5Tget_size(type.get());
  std::string buffer(size, '\0');
  Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mem.get(), size);
  H5Tset_strpad(mem.get(), H5T_STR_NULLPAD);
  if (size > 0 && H5Aread(attr.get(), mem.get(), buffer.data()) < 0) {
    Fail(path_, where + ": read failed");
  }
  // Fixed-length strings are padded with NULs or spaces depending on the writer.
  const size_t end = buffer.find('\0');
  if (end != std::string::npos) buffer.resize(end);
  if (H5Tget_strpad(type.get()) == H5T_STR_SPACEPAD) {
    while (!buffer.empty() && buffer.back() == ' ') buffer.pop_back();
  }
  return buffer;
}

std::vector<std::string> File::ListAttributes(const std::string& object_path) const {
  RequireOpen();
  ErrorSilencer silence;
  Handle obj = OpenObject(id_, path_, object_path);
  std::vector<std::string> names;
  auto callback = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t index = 0;
  H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_INC, &index, callback, &names);
  return names;
}

std::vector<std::string> File::ListDatasets() const {
  RequireOpen();
  ErrorSilencer silence;
  struct Visit {
    hid_t file;
    std::vector<std::string> paths;
  } visit{id_, {}};
  // H5Lvisit walks every link below the root (relative names, no leading '/').
  auto callback = [](hid_t group, const char* name, const H5L_info_t* info, void* data) -> herr_t {
    if (info->type != H5L_TYPE_HARD) return 0;
    H5O_info_t oinfo;
    if (H5Oget_info_by_name(group, name, &oinfo, H5P_DEFAULT) < 0) return 0;
    if (oinfo.type == H5O_TYPE_DATASET) {
      static_cast<Visit*>(data)->paths.push_back(std::string("/") + name);
    }
    return 0;
  };
  H5Lvisit(id_, H5_INDEX_NAME, H5_ITER_INC, callback, &visit);
  std::sort(visit.paths.begin(), visit.paths.end());
  return visit.paths;
}

}  // namespace spallkit::h5
