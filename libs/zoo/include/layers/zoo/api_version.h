// layers/zoo/api_version.h -- the version of the plugin API (model.h,
// registry.h, plugin.h, plugin_abi.h; v2: the ABI handshake). Bump it
// whenever a change to those headers breaks
// binary compatibility; plugins built for another version are refused with
// a message asking to rebuild them. The #ifndef exists only so that a test
// plugin can be compiled with a wrong version; do not override it otherwise.
#pragma once

#ifndef LAYERS_ZOO_API_VERSION
#define LAYERS_ZOO_API_VERSION 2
#endif
