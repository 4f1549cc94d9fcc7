// HDF5 as the extractor's file reader and writer call it: the library set up once, every call
// checked (a failure throws with HDF5's reason, e.g. the system's "No space left on device"),
// identifiers owned and closed.
#pragma once

#include <hdf5.h>

#include <string>

namespace mixflow::mx::h5 {

// Before any other HDF5 call: no exit handler (see H5Output.h) and no error printing (failures
// are reported through exceptions).
void initHdf5();

// Throws std::runtime_error "HDF5: <what> (<HDF5's reason>)".
[[noreturn]] void h5fail(const std::string& what);

// The identifier or status; h5fail(what + " failed") when it is negative.
hid_t check(hid_t id, const std::string& what);
void check(herr_t e, const std::string& what);

// Owns an HDF5 identifier.
class Id {
 public:
  Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Id() {
    if (id_ >= 0) close_(id_);
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

}  // namespace mixflow::mx::h5
