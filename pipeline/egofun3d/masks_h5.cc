#include "pipeline/egofun3d/masks_h5.h"

#include <hdf5.h>

#include <filesystem>

namespace efc::egofun3d {
namespace {

constexpr const char* kCode = "E1044";

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

// HDF5 prints its error stack to stderr by default; the importer reports
// problems itself, in efc's format.
void silence_hdf5() {
  static const bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

}  // namespace

MaskFile::~MaskFile() {
  for (long long d : datasets_)
    if (d >= 0) H5Dclose(static_cast<hid_t>(d));
  if (file_ >= 0) H5Fclose(static_cast<hid_t>(file_));
}

bool MaskFile::open(const std::string& path, Diagnostics& diags) {
  silence_hdf5();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    diags.error(kCode, path, 0, 0, "", "the mask file does not exist");
    return false;
  }
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    diags.error(kCode, path, 0, 0, "", "is not an HDF5 file");
    return false;
  }
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) {
    diags.error(kCode, path, 0, 0, "", "the HDF5 file cannot be opened");
    return false;
  }
  file_ = file;
  std::vector<std::string> names;
  hsize_t idx = 0;
  if (H5Literate(file, H5_INDEX_NAME, H5_ITER_INC, &idx, collect_name, &names) < 0) {
    diags.error(kCode, path, 0, 0, "", "the HDF5 file's top level cannot be listed");
    return false;
  }
  bool ok = true;
  for (const std::string& name : names) {
    H5O_info_t info;
    if (H5Oget_info_by_name(file, name.c_str(), &info, H5P_DEFAULT) < 0 || info.type != H5O_TYPE_GROUP) continue;
    auto bad = [&](const std::string& message) {
      diags.error(kCode, path, 0, 0, "/" + name, "group '" + name + "': " + message,
                  "each part is a group with an integer attribute mask_idx and a dataset masks (T, H, W)");
      ok = false;
    };
    const hid_t group = H5Gopen2(file, name.c_str(), H5P_DEFAULT);
    if (group < 0) {
      bad("cannot be opened");
      continue;
    }
    MaskGroup mg;
    mg.label = name;
    if (H5Aexists(group, "mask_idx") <= 0) {
      bad("has no attribute mask_idx");
      H5Gclose(group);
      continue;
    }
    const hid_t attr = H5Aopen(group, "mask_idx", H5P_DEFAULT);
    const hid_t atype = attr >= 0 ? H5Aget_type(attr) : -1;
    const hid_t aspace = attr >= 0 ? H5Aget_space(attr) : -1;
    int value = 0;
    const bool attr_ok = attr >= 0 && H5Tget_class(atype) == H5T_INTEGER &&
                         H5Sget_simple_extent_npoints(aspace) == 1 &&
                         H5Aread(attr, H5T_NATIVE_INT, &value) >= 0;
    if (aspace >= 0) H5Sclose(aspace);
    if (atype >= 0) H5Tclose(atype);
    if (attr >= 0) H5Aclose(attr);
    if (!attr_ok) {
      bad("attribute mask_idx is not one integer");
      H5Gclose(group);
      continue;
    }
    mg.mask_idx = value;
    if (H5Lexists(group, "masks", H5P_DEFAULT) <= 0) {
      bad("has no dataset 'masks'");
      H5Gclose(group);
      continue;
    }
    // A chunk cache large enough for a few compressed chunks: reading one
    // frame at a time must not decompress the same chunk once per frame.
    const hid_t dapl = H5Pcreate(H5P_DATASET_ACCESS);
    H5Pset_chunk_cache(dapl, 12421, 64u << 20, 1.0);
    const hid_t dset = H5Dopen2(group, "masks", dapl);
    H5Pclose(dapl);
    H5Gclose(group);
    if (dset < 0) {
      bad("dataset 'masks' cannot be opened");
      continue;
    }
    const hid_t space = H5Dget_space(dset);
    hsize_t dims[3] = {0, 0, 0};
    const int rank = H5Sget_simple_extent_ndims(space);
    if (rank == 3) H5Sget_simple_extent_dims(space, dims, nullptr);
    H5Sclose(space);
    const hid_t dtype = H5Dget_type(dset);
    const H5T_class_t cls = H5Tget_class(dtype);
    H5Tclose(dtype);
    if (rank != 3 || dims[0] == 0 || dims[1] == 0 || dims[2] == 0) {
      bad("dataset 'masks' is not a non-empty (T, H, W) array (rank " + std::to_string(rank) + ")");
      H5Dclose(dset);
      continue;
    }
    if (cls != H5T_INTEGER && cls != H5T_ENUM && cls != H5T_FLOAT && cls != H5T_BITFIELD) {
      bad("dataset 'masks' is not numeric (bool, integer or float)");
      H5Dclose(dset);
      continue;
    }
    mg.frames = dims[0];
    mg.height = dims[1];
    mg.width = dims[2];
    groups_.push_back(mg);
    datasets_.push_back(dset);
  }
  return ok;
}

bool MaskFile::read_frame(size_t g, unsigned long long t, std::vector<uint8_t>* out, std::string* error) const {
  const MaskGroup& mg = groups_[g];
  const hid_t dset = static_cast<hid_t>(datasets_[g]);
  const hid_t ftype = H5Dget_type(dset);
  // Read in the dataset's own (native) element type, then test each element
  // for any non-zero byte: works for bool enums, integers of any width and
  // floats alike, with no conversion path HDF5 might not have.
  const hid_t mtype = H5Tget_native_type(ftype, H5T_DIR_ASCEND);
  H5Tclose(ftype);
  const size_t es = H5Tget_size(mtype);
  const size_t n = static_cast<size_t>(mg.height * mg.width);
  std::vector<uint8_t> raw(n * es);
  const hid_t fspace = H5Dget_space(dset);
  const hsize_t start[3] = {t, 0, 0}, count[3] = {1, mg.height, mg.width};
  H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr);
  const hsize_t mdims[1] = {n};
  const hid_t mspace = H5Screate_simple(1, mdims, nullptr);
  const herr_t rc = H5Dread(dset, mtype, mspace, fspace, H5P_DEFAULT, raw.data());
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Tclose(mtype);
  if (rc < 0) {
    *error = "group '" + mg.label + "': frame " + std::to_string(t) + " of 'masks' cannot be read";
    return false;
  }
  out->assign(n, 0);
  for (size_t i = 0; i < n; ++i)
    for (size_t b = 0; b < es; ++b)
      if (raw[i * es + b]) {
        (*out)[i] = 255;
        break;
      }
  return true;
}

}  // namespace efc::egofun3d
