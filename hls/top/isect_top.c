/* Unit-triangle intersection unit top function (paper section 2.1, Table 2: 3 add, 2 mul,
 * 1 div; one more add for the rebased distance te + t'): see hls_top.h. */
#include "hls_top.h"

void isect_top(const isect_txn in[HLS_BATCH], isect_result out[HLS_BATCH], uint32_t n)
{
#pragma HLS INTERFACE mode=axis port=in
#pragma HLS INTERFACE mode=axis port=out
#pragma HLS INTERFACE mode=s_axilite port=n
#pragma HLS INTERFACE mode=s_axilite port=return
isect_stream:
    for (uint32_t i = 0; i < HLS_BATCH; i++) {
#pragma HLS PIPELINE II=1
        if (i >= n)
            break;
        out[i] = isect_unit_triangle(in[i].o, in[i].d, in[i].te, in[i].tmin, in[i].tmax, in[i].shared);
    }
}
