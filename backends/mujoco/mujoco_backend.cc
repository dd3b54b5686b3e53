// Implemented by the MuJoCo backend work (mujoco_backend.h).
