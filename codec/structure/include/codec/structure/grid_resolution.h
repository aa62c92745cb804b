#pragma once

namespace codec {

// A JP2 resolution (T.800 I.5.3.7): points per metre of a reference grid, vertically and
// horizontally; both 0 where there is none. The encoder writes it into JP2/JPH resolution boxes;
// the decoder reports a file's on the decoded image's (reduced) grid.
struct GridResolution {
  double vertical = 0, horizontal = 0;
  bool given() const { return vertical > 0 && horizontal > 0; }
};

}  // namespace codec
