/* hl_sweep_write's HDF5 branch.  A placeholder until the HDF5 writer
 * (helper "h5", branch i15-h5) replaces this file: HL_EUNSUP, nothing
 * written. */
#include "sweep/sweep_impl.h"

hl_status hl_sweep_write_h5(const hl_sweep *sw, const hl_sweep_table *tab, const char *path,
                            hl_error *err)
{
    (void)sw;
    (void)tab;
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                        "cannot write '%s': HDF5 output is not built yet (write .csv)", path);
}
