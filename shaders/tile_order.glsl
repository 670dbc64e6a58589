// Which image tile a workgroup of a per-pixel pass works on. Binder: TileOrderPiece (render/shader_pieces.h),
// which also dispatches.
//
// llvmpipe (Mesa's compute thread pool, lp_cs_tpool.c) hands each worker thread one contiguous run of a
// dispatch's workgroups: groups / threads of them in gl_WorkGroupID order (x fastest). In scanline order the
// threads so get the upper and the lower part of the image, and where rays through one part cost more (the
// face below the skull, the air around it) one thread idles while the other finishes. Here the rows of tiles
// are dealt out from `tileBands` horizontal bands in turn: the j-th row of the dispatch is row
// (j mod B) * m + j / B of the image (m rows per band), so every contiguous run of groups covers every band
// alike, while each row is still walked left to right (neighbouring rays, neighbouring texels): with m rows
// per band, each of up to m threads gets rows from every band (two threads: the first and the second half of
// every band). The dispatch has B * m rows (up to m - 1 more than the image); groups past the last row do
// nothing. m = 1: scanline order.
// A dispatch may cover a run of bands only (the exact frame in slices, Renderer::advanceExact): bands
// firstBand .. firstBand + tileBands - 1, dealt out the same way, so each slice is a horizontal strip of the
// image that the threads share alike, and the slices of a frame together shade every pixel once.
// A dispatch may also cover a run of columns of one band only, from firstColumn (a part of a band: the exact
// frame's slices on an image where one band costs more than a slice may).
// A dispatch may also cover, per row of tiles, only the run of columns in tileSpans (the dispatch as wide as the
// widest): the exact frame that casts again only the pixels a clip mesh's motion can change
// (render/recast_region.h). A pixel is shaded by the same invocation code either way.
#include "bindings.glsl"

uniform uint tileBands;       // B: the bands this dispatch covers (all: ceil(tile rows / m))
uniform uint firstBand;       // the first of them
uniform uint rowsPerBand;     // m
uniform uint firstColumn;     // the dispatch's first column of tiles (of the span, with tileSpansOn)
uniform uvec2 tileGrid;       // tiles across and down
uniform bool tileSpansOn;      // cover only the tiles of each row's span
layout(std430, binding = SSBO_TILE_SPANS) readonly buffer TileSpans { uvec2 tileSpans[]; };   // per row of tiles: [first, end)

// Which pixel of its tile an invocation shades. llvmpipe runs a work group 8 invocations at a time (a 256-bit
// vector of 32-bit lanes), in gl_LocalInvocationIndex order, and a vector's sample loop runs until its longest ray
// is done. Rays through nearby pixels end at similar depths, so each run of 8 invocations shades a block 2 pixels
// wide and 4 high rather than a row of 8 (the blocks in rows across the tile): the head's phong ray cast
// (`bench raycast`, 512x512, minimum over 16 frames, three runs each, alternately) took 194.6 / 194.9 / 203.3 ms
// against 212.3 / 215.2 / 215.8 ms with rows of 8, and 4 x 2 blocks 202.1 / 205.0 / 203.2 ms; solid was within
// the noise. On a GPU, 32 or 64 lanes take 4 or 8 such blocks: 8 x 4 or 8 x 8 pixels. Which invocation shades a
// pixel changes nothing in it. Needs tileSize.x even and tileSize.y a multiple of 4.
uvec2 pixelInTile(uvec2 tileSize) {
    uint l = gl_LocalInvocationIndex;
    uint block = l >> 3u, lane = l & 7u, blocksAcross = tileSize.x / 2u;
    return uvec2((block % blocksAcross) * 2u + (lane & 1u), (block / blocksAcross) * 4u + (lane >> 1u));
}

// The pixel this invocation shades; false when its group lies past the last row of tiles.
bool tilePixel(uvec2 tileSize, out ivec2 pixel) {
    uint j = gl_WorkGroupID.y;
    uint row = (firstBand + j % tileBands) * rowsPerBand + j / tileBands;
    uint column = firstColumn + gl_WorkGroupID.x;
    bool inside = row < tileGrid.y && column < tileGrid.x;
    if (tileSpansOn && inside) {
        uvec2 span = tileSpans[row];
        column += span.x;
        inside = column < span.y;
    }
    pixel = ivec2(uvec2(column, row) * tileSize + pixelInTile(tileSize));
    return inside;
}

// Whether this group lies in the first half of the dispatch (as two worker threads split it; for `bench`).
bool inFirstHalfOfDispatch() {
    return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x < gl_NumWorkGroups.x * gl_NumWorkGroups.y / 2u;
}
