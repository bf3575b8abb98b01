// A fixture of the layering test: core may include no other module, so this include must be refused.
#include "fitlib/segment/mesh.hpp"
