# run by execfile_main.py through execfile with an explicit globals dict
q = k * 14
