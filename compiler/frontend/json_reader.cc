// Implemented by the front-end work (json_reader.h).
