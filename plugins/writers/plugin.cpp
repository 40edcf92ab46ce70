// The writers plugin: HDF5 (H5Part) time series, VTK XML series, CSV probes.
#include "talus/plugin.hpp"

#include "hdf5_writer.hpp"
#include "probes_writer.hpp"
#include "vtu_writer.hpp"

TALUS_PLUGIN("talus-writers", "0.1.0",
             talus::model_entry<talus::writers::Hdf5Writer>(
                 "writer", "hdf5", "particle fields as an H5Part time series (ParaView, h5py), block states alongside"),
             talus::model_entry<talus::writers::VtuWriter>(
                 "writer", "vtu", "VTK XML: one .vtu per frame and a .pvd collection (ParaView)"),
             talus::model_entry<talus::writers::ProbesWriter>(
                 "writer", "probes", "CSV time series: fields at points, wave gauges, integral quantities"));
