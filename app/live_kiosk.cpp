// The live kiosk (see live_kiosk.h).
#include "live_kiosk.h"

namespace sas::app {

int RunKiosk(const std::vector<std::string>& /*args*/, std::FILE* /*out*/, std::FILE* err) {
  std::fprintf(err, "sketch-a-scratch: the live kiosk is not wired yet\n");
  return 1;
}

}  // namespace sas::app
