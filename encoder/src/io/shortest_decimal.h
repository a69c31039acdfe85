// The shortest decimal that reads back as the same float, for text files: 0.1, not
// 0.10000000149011612, and the same double for every reader of the file.
#ifndef M4D_ENCODER_IO_SHORTEST_DECIMAL_H_
#define M4D_ENCODER_IO_SHORTEST_DECIMAL_H_

namespace m4d {

// That decimal as a double (the value a JSON reader gets back); never -0.0.
double ShortestDecimal(float value);

}  // namespace m4d

#endif  // M4D_ENCODER_IO_SHORTEST_DECIMAL_H_
