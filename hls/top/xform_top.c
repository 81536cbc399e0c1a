/* Transformation unit top function (paper section 2.1, Table 2: 9 add, 9 mul): see hls_top.h. */
#include "hls_top.h"

void xform_top(const xform_txn in[HLS_BATCH], f24_vec3 out[HLS_BATCH], uint32_t n)
{
#pragma HLS INTERFACE mode=axis port=in
#pragma HLS INTERFACE mode=axis port=out
#pragma HLS INTERFACE mode=s_axilite port=n
#pragma HLS INTERFACE mode=s_axilite port=return
xform_stream:
    for (uint32_t i = 0; i < HLS_BATCH; i++) {
#pragma HLS PIPELINE II=1
        if (i >= n)
            break;
        out[i] = in[i].point ? xform_point(&in[i].m, in[i].v) : xform_vector(&in[i].m, in[i].v);
    }
}
