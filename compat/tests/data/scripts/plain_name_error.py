print('before')
x = notAYadeNameAtAll + 1
