// A thin RAII wrapper over the HDF5 C API (Debian libhdf5 1.10), just wide enough for spallkit's
// data contract: 1-D (and a few 2-D) float64 datasets with scalar attributes.
//
// Why a wrapper of our own: HighFive and h5cpp are not packaged by Debian, and spallkit needs only
// a dozen operations. The wrapper
//  - owns every hid_t it opens (nothing leaks on an exception),
//  - never lets HDF5 print its error stack (library code does not print); failures become one
//    InputError line naming the file, the object and what was expected,
//  - writes float64 (H5T_IEEE_F64LE) and reads any numeric type converted to double,
//  - writes string attributes as variable-length UTF-8, which h5py reads as `str` (fixed-length
//    strings come back as `bytes`); it reads both kinds.
//
// Layout written by `spall simulate` (docs/BEARING_MODEL.md, "Output file"):
//   /                 attributes spallkit_version, scene (strings)
//   /time             float64 [n]
//   /signals/accel_y  float64 [n], attributes sample_rate_hz (double), units (string)
//   /signals/accel_z  idem
//   /contact/...      float64 [n x rollers] (row-major: one row per time sample)
//
// Paths are absolute HDF5 paths ("/signals/accel_y"); a missing leading '/' is added. The root
// object is "/".
//
// Atomic output: File::Create truncates the file it is given. To publish a file only when it is
// complete, create it on AtomicFile::temp_path(), write, Close(), then AtomicFile::Commit().
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace spallkit::h5 {

class File {
 public:
  // Creates (truncating) a new file. Throws InputError naming the path when it cannot.
  static File Create(const std::string& path);
  // Opens an existing file read-only. Throws InputError naming the path when the file is missing
  // or is not an HDF5 file.
  static File OpenReadOnly(const std::string& path);

  File(File&& other) noexcept;
  File& operator=(File&& other) noexcept;
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  ~File();

  // Flushes and closes the file now (the destructor does it otherwise). Further calls throw.
  // Throws InputError if HDF5 reports a failure while closing (e.g. disk full).
  void Close();
  bool is_open() const { return id_ >= 0; }
  const std::string& path() const { return path_; }

  // Writes a 1-D float64 dataset, creating missing parent groups. An existing dataset of that
  // name is replaced.
  void WriteDataset(const std::string& path, std::span<const double> data);
  // Writes a 2-D float64 dataset [rows x cols] from row-major data (size rows*cols). h5py sees
  // shape (rows, cols); MATLAB's h5read shows the transpose, as always for HDF5.
  void WriteDataset2D(const std::string& path,
                      std::span<const double> row_major,
                      size_t rows,
                      size_t cols);
  // Creates a group (and its parents) if it does not exist yet.
  void CreateGroup(const std::string& path);

  // Scalar attributes on a group or dataset ("/" for the root). Replaces an existing attribute.
  void SetAttribute(const std::string& object_path, const std::string& name, double value);
  void SetAttribute(const std::string& object_path,
                    const std::string& name,
                    const std::string& value);
  // Overload so that a string literal does not silently pick the bool -> double conversion.
  void SetAttribute(const std::string& object_path, const std::string& name, const char* value) {
    SetAttribute(object_path, name, std::string(value));
  }

  // True when a link exists at every level of `path` (a group or a dataset). "/" always exists.
  bool Exists(const std::string& path) const;
  // True when `path` exists and is a dataset.
  bool IsDataset(const std::string& path) const;

  // Reads a numeric dataset of any rank as doubles, flattened row-major (C order). If `dims` is
  // given it receives the shape. Throws InputError "<file>: <path>: ..." when the dataset is
  // missing or not numeric.
  std::vector<double> ReadDataset(const std::string& path,
                                  std::vector<size_t>* dims = nullptr) const;
  // The shape of a dataset without reading it.
  std::vector<size_t> DatasetDims(const std::string& path) const;

  // A scalar (or single-element) numeric attribute; nullopt when the object has no attribute of
  // that name. Throws InputError when the object is missing or the attribute is not numeric.
  std::optional<double> ReadDoubleAttribute(const std::string& object_path,
                                            const std::string& name) const;
  // A string attribute (variable- or fixed-length); nullopt when absent. Throws InputError when
  // the object is missing or the attribute is not a string.
  std::optional<std::string> ReadStringAttribute(const std::string& object_path,
                                                 const std::string& name) const;
  // Attribute names of an object, in creation/name order.
  std::vector<std::string> ListAttributes(const std::string& object_path) const;

  // All dataset paths in the file, recursively, sorted ("/signals/accel_y", "/time", ...).
  std::vector<std::string> ListDatasets() const;

 private:
  File(long long id, std::string path) : id_(id), path_(std::move(path)) {}
  void RequireOpen() const;

  long long id_ = -1;  // hid_t (int64_t in HDF5 >= 1.10); kept as long long to keep hdf5.h private
  std::string path_;
};

}  // namespace spallkit::h5
