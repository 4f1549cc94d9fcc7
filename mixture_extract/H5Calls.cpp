#include "H5Calls.h"

#include <stdexcept>

namespace mixflow::mx::h5 {

namespace {

// The reason HDF5 gives for the last failure: the system's message (e.g. "No space left on
// device") when a read or write failed, else the innermost error description.
std::string h5reason() {
  struct Found {
    std::string inner, system;
  } found;
  auto cb = [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
    Found& f = *static_cast<Found*>(data);
    const std::string desc = e->desc ? e->desc : "";
    if (n == 0) f.inner = desc;
    const std::string key = "error message = '";
    const size_t b = desc.find(key);
    if (f.system.empty() && b != std::string::npos) {
      const size_t e2 = desc.find('\'', b + key.size());
      f.system = desc.substr(b + key.size(), e2 == std::string::npos ? e2 : e2 - b - key.size());
    }
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, cb, &found);
  return !found.system.empty() ? found.system : found.inner;
}

}  // namespace

[[noreturn]] void h5fail(const std::string& what) {
  const std::string why = h5reason();
  throw std::runtime_error("HDF5: " + what + (why.empty() ? std::string() : " (" + why + ")"));
}

void initHdf5() {
  static const bool done = [] {
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) h5fail(what + " failed");
  return id;
}
void check(herr_t e, const std::string& what) {
  if (e < 0) h5fail(what + " failed");
}

}  // namespace mixflow::mx::h5
