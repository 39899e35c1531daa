#include "app/render/sky_settings.h"

namespace cb {

const char* skyKindName(SkyKind kind) {
  switch (kind) {
    case SkyKind::kNone:
      return "none";
    case SkyKind::kColour:
      return "colour";
    case SkyKind::kLic:
      return "lic";
    case SkyKind::kImage:
      return "image";
  }
  return "none";
}

bool parseSkyKind(const std::string& name, SkyKind* kind) {
  for (SkyKind k : {SkyKind::kNone, SkyKind::kColour, SkyKind::kLic, SkyKind::kImage})
    if (name == skyKindName(k)) {
      *kind = k;
      return true;
    }
  return false;
}

}  // namespace cb
