/* Traversal unit's per-node decision for a 4-ray packet (paper sections 3 and 4.3, Table 2:
 * 4 add, 4 div, 13 cmp): see hls_top.h. */
#include "hls_top.h"

void trav_top(const trav_txn in[HLS_BATCH], trav_result out[HLS_BATCH], uint32_t n)
{
#pragma HLS INTERFACE mode=axis port=in
#pragma HLS INTERFACE mode=axis port=out
#pragma HLS INTERFACE mode=s_axilite port=n
#pragma HLS INTERFACE mode=s_axilite port=return
#pragma HLS AGGREGATE variable=in
#pragma HLS AGGREGATE variable=out
trav_stream:
    for (uint32_t i = 0; i < HLS_BATCH; i++) {
#pragma HLS PIPELINE II=1
        if (i >= n)
            break;
        trav_result r;
        trav_node_split(&in[i].e, in[i].axis, in[i].split, in[i].o, in[i].d, &r.l, &r.r, &r.near_left);
        out[i] = r;
    }
}
