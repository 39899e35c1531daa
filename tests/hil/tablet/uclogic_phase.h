// The `uclogic` phase of the virtual tablet test: a Huion tablet (256c:006e) as a real USB
// device on the dummy UDC through GadgetFS (gadgetfs_device.h), so that the kernel's own
// hid-uclogic binds it, reads its vendor string descriptors (index 201: firmware name, 200: the
// v2 pen parameters), replaces its report descriptor and rewrites its raw vendor reports. The
// pen script then goes in as raw vendor reports and must come out the same on evdev and on our
// hidraw decode of the descriptor hidraw shows, field by field.
#pragma once

#include <string>

namespace cb::hil {

// Runs the phase, printing "CB-HIL CHECK" and "CB-HIL FIGURE" lines; returns failed checks.
int runUclogicPhase(const std::string& fixture_dir);

}  // namespace cb::hil
