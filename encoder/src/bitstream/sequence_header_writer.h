// Serialisation of the SEQUENCE_HEADER payload (bitstream-spec 4.1).
#ifndef M4D_ENCODER_BITSTREAM_SEQUENCE_HEADER_WRITER_H_
#define M4D_ENCODER_BITSTREAM_SEQUENCE_HEADER_WRITER_H_

#include "sdk/src/bitstream/sequence_header.h"
#include "sdk/src/common/byte_writer.h"

namespace m4d {

// Validates the header (ranges of spec 4.1) and writes it.
Status WriteSequenceHeader(const SequenceHeader& header, ByteWriter* out);

}  // namespace m4d

#endif  // M4D_ENCODER_BITSTREAM_SEQUENCE_HEADER_WRITER_H_
